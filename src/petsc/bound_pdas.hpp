// The petsc backend's solver of the bound QP in PETSc, on rank-local data:
//
//     minimise ½ vᵀ A v − bᵀ v   subject to   v_i ≤ upper_i  (i bounded)
//
// by the primal-dual active-set method (a semismooth Newton method) at about the cost of one
// linear multigrid solve of A (docs/petsc-measurements.md, "The contact solve"):
//   - one multigrid hierarchy (multigrid.hpp), set up once, on A;
//   - each step's system with the active rows fixed is W x = rhs (masked_system.hpp), solved by
//     CG preconditioned by that hierarchy, whose coarse operators follow the fixed rows by local
//     updates (truncation.hpp) — so a step costs what a linear solve from its start costs;
//   - for quadratic elements the same contact problem on the P1 level (a bound at each candidate
//     vertex, the P1 Galerkin operator, 1/8 of the rows) is solved first and interpolated: the
//     fine loop starts at the P1 answer's active set and needs few, short steps;
//   - inexact steps: while the active set changes a step's CG only reduces its residual tenfold;
//     a step whose active set repeats is solved at the final rule, and only such a step ends the
//     loop, so the certificate holds as with exact steps.
#pragma once

#include <petscksp.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "contactqp/qp.hpp"
#include "multigrid.hpp"

namespace contactqp::detail {

// The problem: the caller's PETSc objects (kept by the caller for the solve).
struct PetscBoundQp {
  Mat A = nullptr;  // SPD; MAT_SPD, block size (dim) and near-null space (rigid-body modes) set
  Vec b = nullptr;
  std::vector<PetscInt> bounded;  // this rank's bounded rows (global, in its ownership range), increasing
  std::vector<double> upper;      // their bounds
  // Quadratic elements (else null / empty): the P2 → P1 interpolation (multigrid.hpp), the
  // rigid-body modes on the P1 level, and per bound the P1 column of its variable when its node
  // is a vertex — the P1 level's columns of a candidate vertex are in its own variables — or −1.
  Mat coarse_interpolation = nullptr;
  MatNullSpace coarse_modes = nullptr;
  std::vector<PetscInt> coarse_bounded;
  // Tresca friction (petsc_bound_qp.hpp's BoundQp), this rank's contact rows with friction:
  // their tangential variables (global rows in this rank's range, n_directions per contact row,
  // consecutive; −1 for a direction without a free DOF, whose λ_T stays 0), offsets and radii.
  // n_directions 0: frictionless.
  int n_directions = 0;
  std::vector<PetscInt> tangential;
  std::vector<double> offset;  // one per entry of `tangential`
  std::vector<double> radius;  // one per contact row: tangential.size() / n_directions
  // The states the loop starts from (a warm start), or empty: 1 per active bound; per contact
  // row with friction 1 where it sticks, and the sign of its slip (one per tangential variable).
  std::vector<char> start_active, start_stick;
  std::vector<double> start_direction;
};

// A loose step's CG reduces its own initial residual by this factor (never below the final
// rule): the next active set needs the step's direction, not its digits. 0.1 measured best
// (docs/petsc-measurements.md, "Inexact steps"); 2–4 CG iterations a step. The backend option
// loose_reduction changes it.
constexpr double kLooseReduction = 0.1;

struct BoundPdasOptions {
  double tol = 1e-8;
  int max_iterations = 10000;                // active-set steps on the fine level
  bool inexact = true;                       // loose steps while the active set changes
  double loose_reduction = kLooseReduction;  // a loose step's CG: its own residual times this
  bool p1_start = true;                      // solve the P1 contact problem first (quadratic elements)
  bool truncate = true;                      // the coarse operators follow the fixed rows (truncation.hpp)
  // The relative KKT residual without stationarity (certificate.hpp's scales) of v and μ (this
  // rank's rows and bounds); collective, the global value. The loop ends when it is ≤ tol after
  // a step solved at the final rule.
  std::function<double(Vec v, const std::vector<double>& mu)> residual;
  // With friction (PetscBoundQp::n_directions > 0): the same with this rank's tangential
  // multipliers λ_T (one per entry of PetscBoundQp::tangential), in place of `residual`.
  std::function<double(Vec v, const std::vector<double>& mu, const std::vector<double>& lambda_t)> friction_residual;
};

// Solves with A after the loop: its KSP and hierarchy, A as operator (no fixed rows), to the
// inner rule ‖r‖₂ ≤ 1e-3 · tol · force. For the certificate's θ: no second set-up.
class SolverOfA {
 public:
  virtual ~SolverOfA() = default;
  virtual bool solve(Vec rhs, Vec x, double force) = 0;  // collective; false on failure
  // θ = rhsᵀA⁻¹rhs (the certificate's rᵀK⁻¹r), by CG from x = 0. CG's rhsᵀx_k grows to θ
  // (x_k minimises the energy on the Krylov space, so rhsᵀx_k = ‖x_k‖²_A), and θ − rhsᵀx_k =
  // ‖x − x_k‖²_A; the solve stops at the inner rule above or as soon as rhsᵀx_k has grown by at
  // most `tolerance` over the last few iterations (the error left, estimated): what the gap
  // needs is θ to an absolute tolerance, which takes a few iterations where the inner rule takes
  // tens. Collective; false on failure.
  virtual bool energy(Vec rhs, Vec x, double force, double tolerance, double* theta) = 0;
  virtual long long iterations() const = 0;  // Krylov iterations of its solves
};

struct BoundPdasResult {
  Status status = Status::NumericalError;
  std::string message;
  Vec v = nullptr;                // A's layout; the result owns it
  std::vector<double> mu;         // one per bound of this rank, ≥ 0
  std::vector<double> lambda_t;   // with friction: one per entry of PetscBoundQp::tangential
  long long stick = 0, slip = 0;  // with friction: contact rows sticking and slipping at the end, all ranks
  int iterations = 0;             // fine active-set steps
  long long krylov_iterations = 0, linear_solves = 0;
  int p1_steps = 0;  // active-set steps of the P1 start (0: none)
  long long p1_krylov_iterations = 0;
  int preconditioner_setups = 0;    // 1: the hierarchy
  long long active = 0;             // bounds active at the end, all ranks
  std::vector<char> active_bounds;  // this rank's: 1 for each of its bounds active at the end
  double residual = 0;
  double setup_seconds = 0, iterate_seconds = 0, p1_seconds = 0, update_seconds = 0;
  MultigridStatistics multigrid;
  std::string method;  // e.g. "pdas, cg + mg: P1 level + gamg, 6 near-null modes, P1 start, truncated"
  std::shared_ptr<SolverOfA> solver_of_A;

  BoundPdasResult() = default;
  BoundPdasResult(BoundPdasResult&& other) noexcept;
  BoundPdasResult& operator=(BoundPdasResult&& other) noexcept;
  BoundPdasResult(const BoundPdasResult&) = delete;
  BoundPdasResult& operator=(const BoundPdasResult&) = delete;
  ~BoundPdasResult();
};

// Collective. Numerical failures come back in status and message; PETSc errors as the code
// (the caller turns them into its message; an error from KSPSetFromOptions or the PC's
// set-up is the user's options: `options_error` is set then).
// Load steps on one A: the solve before, of the same A and bounded rows with another b and other
// bounds, lends its hierarchy and KSP (no set-up: preconditioner_setups 0) and its answer, where
// the loop starts (no P1 start).
struct WarmStart {
  std::shared_ptr<SolverOfA> solver_of_A;  // that solve's (BoundPdasResult::solver_of_A)
  Vec v = nullptr;                         // its v, copied
  std::vector<char> active_bounds;         // its active set on this rank's bounds
  MultigridStatistics multigrid;           // its hierarchy's, reported again
};

PetscErrorCode solve_bound_pdas(const PetscBoundQp& qp, const BoundPdasOptions& options, BoundPdasResult* result,
                                bool* options_error, const WarmStart* start = nullptr);

}  // namespace contactqp::detail
