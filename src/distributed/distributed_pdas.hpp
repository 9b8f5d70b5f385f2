// The petsc backend's contact solve on a distributed bound QP (distributed_problem.hpp): every
// rank holds its rows of A, b and its own bounds and multipliers, nothing whole. The method is
// the petsc backend's own (bound_pdas.hpp: the primal-dual active-set loop with one multigrid
// hierarchy kept for the whole contact solve, a P1 level for quadratic elements, inexact steps);
// this file hands the distributed problem to it and agrees its outcome over the ranks.
#pragma once

#include <petscksp.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "contactqp/qp.hpp"
#include "distributed_problem.hpp"
#include "petsc/bound_pdas.hpp"

namespace contactqp::detail {

struct DistributedPdasOptions {
  double tol = 1e-8;
  int max_iterations = 10000;
  std::string petsc_options;
  bool inexact = true;                       // loose CG solves while the active set changes
  double loose_reduction = kLooseReduction;  // a loose step's CG reduces its residual by this factor
  bool p1_start = true;                      // quadratic elements: the P1 contact problem first
  // --no-contact: the bounds dropped, so the loop is one linear solve A v = b by the same KSP
  // and hierarchy, at the final rule (the contact solve's reference; μ = 0 at every bound).
  bool without_bounds = false;
  // The relative KKT residual without stationarity (certificate.hpp) of this rank's v and μ (one
  // per own bound); collective: returns the global value.
  std::function<double(Vec v, const std::vector<double>& mu)> residual;
};

struct DistributedPdasResult {
  Status status = Status::NumericalError;
  std::string message;
  Vec v = nullptr;         // A's layout; destroyed with the result
  std::vector<double> mu;  // one per own bound, ≥ 0
  int iterations = 0;
  long long krylov_iterations = 0, linear_solves = 0;
  int preconditioner_setups = 0;
  long long active = 0;             // bounds active at the end, all ranks
  std::vector<char> active_bounds;  // this rank's, 1 where active (the next load step's start)
  MultigridStatistics multigrid;    // the hierarchy's
  double residual = 0;
  double setup_seconds = 0, iterate_seconds = 0;
  std::string method;
  double matrix_bytes = 0, petsc_bytes = 0;  // the largest rank's: A, and A with the hierarchy
  int multigrid_levels = 0;                  // the hierarchy's, P1 level included (0: no multilevel preconditioner)
  double grid_complexity = 0, operator_complexity = 0;  // its rows and nonzeros over A's
  std::vector<std::string> warnings;
  // The loop's hierarchy, for the certificate's one solve with A (θ): no second set-up.
  std::shared_ptr<SolverOfA> solver_of_A;

  DistributedPdasResult() = default;
  DistributedPdasResult(DistributedPdasResult&& other) noexcept;
  DistributedPdasResult& operator=(DistributedPdasResult&& other) noexcept;
  DistributedPdasResult(const DistributedPdasResult&) = delete;
  DistributedPdasResult& operator=(const DistributedPdasResult&) = delete;
  ~DistributedPdasResult();
};

// Collective. InputError for bad PETSc options (on every rank); numerical failures in status.
// With `previous` (a load step's solve before this one, on the same A, converged): its
// hierarchy, no second set-up, and its answer as the start.
DistributedPdasResult solve_distributed_pdas(const DistributedBoundQp& qp, const DistributedPdasOptions& options,
                                             const DistributedPdasResult* previous = nullptr);

}  // namespace contactqp::detail
