// What the backends share besides the QP (each backend registers itself in its own file,
// contactqp/backend.hpp): the solver of K they work with, and how its statistics reach the result.
// A backend receives a validated (and, unless disabled, scaled) QP and returns a SolveResult
// whose u and λ are finite; solve() checks that once more.
#pragma once

#include <memory>

#include "contactqp/backend.hpp"
#include "contactqp/linear_solver.hpp"
#include "contactqp/qp.hpp"
#include "qp/builtins.hpp"

namespace contactqp::detail {

// How to build a solver of qp.K as `options` ask (kind, ordering, inner tolerance from
// options.tol, near-null space from qp, the libraries' options).
LinearSolverOptions linear_solver_options(const QuadraticProgram& qp, const SolveOptions& options);

// The solver of qp.K a backend works with: options.K_factor when the caller supplied one,
// otherwise a fresh one of the kind options.linear_solver names (inner tolerance from
// options.tol, near-null space from qp), whose set-up time is recorded in timings as
// "factorize". Null with `message` set when the set-up failed (K not positive definite, ...).
std::shared_ptr<const LinearSolver> factor_of_K(const QuadraticProgram& qp, const SolveOptions& options,
                                                Timings& timings, std::string& message);

// The solver of K's Krylov iterations and solves into result.diagnostics (iterative solvers
// only: "krylov_iterations", "linear_solves") and its warnings into result.warnings.
void report_linear_solver(SolveResult& result);
// The same with the statistics taken at a chosen moment (before the certificate solved with K).
void report_linear_solver(SolveResult& result, const LinearSolverStatistics& statistics);

}  // namespace contactqp::detail
