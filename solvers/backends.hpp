// Entry points of the backends, one per file in solvers/, dispatched by registry.cpp.
// Each receives a validated (and, unless disabled, scaled) QP and returns a SolveResult
// whose u and λ are finite; the registry checks that once more.
#pragma once

#include <memory>

#include "contactqp/linear_solver.hpp"
#include "contactqp/qp.hpp"

namespace contactqp::detail {

SolveResult solve_uzawa(const QuadraticProgram& qp, const SolveOptions& options);
SolveResult solve_uzawa_accelerated(const QuadraticProgram& qp, const SolveOptions& options);
SolveResult solve_ipopt(const QuadraticProgram& qp, const SolveOptions& options);
SolveResult solve_nlopt(const QuadraticProgram& qp, const SolveOptions& options);

// Throw InputError when SolveOptions::backend_options hold a key or value the backend
// does not accept; called before any work.
void check_ipopt_options(const SolveOptions& options);
void check_nlopt_options(const SolveOptions& options);
void check_active_set_options(const SolveOptions& options);
SolveResult solve_active_set(const QuadraticProgram& qp, const SolveOptions& options);
void check_petsc_options(const SolveOptions& options);
SolveResult solve_petsc(const QuadraticProgram& qp, const SolveOptions& options);

// The solver of qp.K a backend works with: options.K_factor when the caller supplied one,
// otherwise a fresh one of the kind options.linear_solver names (inner tolerance from
// options.tol, near-null space from qp), whose set-up time is recorded in timings as
// "factorize". Null with `message` set when the set-up failed (K not positive definite, ...).
std::shared_ptr<const LinearSolver> factor_of_K(const QuadraticProgram& qp, const SolveOptions& options,
                                                Timings& timings, std::string& message);

// The solver of K's Krylov iterations and solves into result.diagnostics (iterative solvers
// only: "krylov_iterations", "linear_solves") and its warnings into result.warnings.
void report_linear_solver(SolveResult& result);

}  // namespace contactqp::detail
