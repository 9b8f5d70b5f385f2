// solve(qp, options): hand the QP to the backend named by options.backend.
//
// Implemented by the registry in solvers/; the backends see only the QuadraticProgram.
#pragma once

#include <vector>

#include "contactqp/qp.hpp"

namespace contactqp {

// Validates the QP and the options (InputError on bad input), optionally scales the problem
// (SolveOptions::scale), runs the backend, and returns its result in the caller's units.
// The QP is left untouched. u and λ in the result are always finite.
SolveResult solve(const QuadraticProgram& qp, const SolveOptions& options);

// The reference a contact solve is measured against: K u = f with the contact rows dropped,
// through the same path as solve() (same scaling, same CHOLMOD factorisation and ordering,
// options.K_factor reused when given). λ = 0 (one entry per row of B), status Converged
// unless K cannot be factorised; timings "factorize" and "solve" (one solve), then "total".
SolveResult solve_without_contact(const QuadraticProgram& qp, const SolveOptions& options);
// The checks solve() makes of the options, backend options included: InputError naming the
// field. For callers that run several solves and want bad input reported before any work.
void validate_options(const SolveOptions& options);

bool backend_available(Backend backend);  // false when its library was not built in
std::vector<Backend> available_backends();
// Whether a backend solves a kind of problem (friction.hpp): every backend solves frictionless
// ones; a frictional problem on a backend that does not solve it is an InputError from solve().
bool backend_supports(Backend backend, ProblemKind kind);   // in 2D at least
std::vector<Backend> available_backends(ProblemKind kind);  // available and supporting `kind`
// The same for one QP: its kind and, with friction, its dimension (nlopt takes 2D friction only).
bool backend_solves(Backend backend, const QuadraticProgram& qp);
std::vector<Backend> available_backends(const QuadraticProgram& qp);

}  // namespace contactqp
