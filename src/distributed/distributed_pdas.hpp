// The petsc backend's primal-dual active-set loop on a distributed bound QP
// (distributed_problem.hpp): every rank holds its rows of A, b, v and its own bounds and
// multipliers, nothing whole (no VecScatterCreateToAll). The method is petsc_bound_qp.cpp's —
// CG + GAMG steps on the full-size matrix with the active rows and columns fixed, inexact steps,
// an optional kept preconditioner — with the active set and its history decided by reductions.
// (The seam with the solver's owner: /work/coord/seam-petsc.md; this is the loop ported to
// local data, for the solver's owner to tune.)
#pragma once

#include <petscksp.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "contactqp/qp.hpp"
#include "distributed_problem.hpp"

namespace contactqp::detail {

struct DistributedPdasOptions {
  double tol = 1e-8;
  int max_iterations = 10000;
  std::string petsc_options;
  bool inexact = true;                // loose KSP solves while the active set changes
  bool reuse_preconditioner = false;  // keep a step's GAMG for the next steps (docs/petsc.md)
  // The relative KKT residual without stationarity (certificate.hpp) of this rank's v and μ (one
  // per own bound); collective: returns the global value.
  std::function<double(Vec v, const std::vector<double>& mu)> residual;
};

// A solver of A for the certificate's one solve (θ): the loop's KSP, A as operator, its last
// preconditioner kept (no new set-up). Collective.
class DistributedSolverOfA {
 public:
  virtual ~DistributedSolverOfA() = default;
  // x = A⁻¹ rhs to the inner rule for `force` (‖r‖₂ ≤ 1e-3 · tol · force); false on failure.
  virtual bool solve(Vec rhs, Vec x, double force) = 0;
};

struct DistributedPdasResult {
  Status status = Status::NumericalError;
  std::string message;
  Vec v = nullptr;         // A's layout; destroyed with the result
  std::vector<double> mu;  // one per own bound, ≥ 0
  int iterations = 0;
  long long krylov_iterations = 0, linear_solves = 0;
  int preconditioner_setups = 0;
  long long active = 0;  // bounds active at the end, all ranks
  double residual = 0;
  double setup_seconds = 0, iterate_seconds = 0;
  std::string method;
  double matrix_bytes = 0, petsc_bytes = 0;  // the largest rank's
  std::vector<std::string> warnings;
  std::shared_ptr<DistributedSolverOfA> solver_of_A;

  DistributedPdasResult() = default;
  DistributedPdasResult(DistributedPdasResult&& other) noexcept;
  DistributedPdasResult& operator=(DistributedPdasResult&& other) noexcept;
  ~DistributedPdasResult();
};

// Collective. InputError for bad PETSc options (on every rank); numerical failures in status.
DistributedPdasResult solve_distributed_pdas(const DistributedBoundQp& qp, const DistributedPdasOptions& options);

}  // namespace contactqp::detail
