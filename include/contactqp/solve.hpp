// solve(qp, options): hand the QP to the backend named by options.backend.
//
// Implemented in solvers/solve.cpp; the backends register themselves (backend.hpp, which lists
// them: available_backends()) and see only the QuadraticProgram.
#pragma once

#include "contactqp/backend.hpp"
#include "contactqp/qp.hpp"

namespace contactqp {

// Validates the QP and the options (InputError on bad input, also for a problem kind the
// backend does not solve: problem_kind(qp)), optionally scales the problem
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

}  // namespace contactqp
