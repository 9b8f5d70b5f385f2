// A bound-constrained QP solved by PETSc on the distributed matrix, seen from the rest of the
// room: no PETSc header here. The petsc backend (petsc_backend.cpp) brings the contact QP to
// this form; petsc_bound_qp.cpp solves it (without_petsc.cpp refuses it when PETSc is absent).
//
//     minimise  ½ vᵀ A v − bᵀ v     subject to   v_i ≤ upper_i  for i in bounded
//
// The multiplier μ_i ≥ 0 of each bound satisfies A v − b + Σ μ_i e_i = 0 at the solution.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "contactqp/linear_solver.hpp"
#include "contactqp/qp.hpp"

namespace contactqp::detail {

struct BoundQp {
  Eigen::SparseMatrix<double> A;     // n × n, symmetric positive definite, both triangles stored
  Eigen::VectorXd b;                 // n
  std::vector<int> bounded;          // the components with an upper bound, increasing
  Eigen::VectorXd upper;             // one bound per entry of `bounded`
  Eigen::MatrixXd near_null_space;   // n × k (rigid-body modes in these variables), or empty
  bool A_is_rank_share = false;      // A is this rank's share: the ranks' shares sum to A (par_qp.hpp)
  std::vector<int> distributed_row;  // the row of each variable in PETSc's matrix, or empty (par_qp.hpp)
  // Quadratic elements (else empty): the P1 level in these variables (coarse_space.hpp, with
  // the columns of a candidate vertex in its own variables), its rigid-body modes, per column
  // its vertex and the variable the vertex carries there (or −1), and per bound the column of
  // its variable when its node is a vertex (or −1): the P1 contact problem of the P1 start.
  Eigen::SparseMatrix<double> coarse_interpolation;
  Eigen::MatrixXd coarse_near_null_space;
  std::vector<int> coarse_vertex, coarse_row, coarse_bounded;
  int coarse_block_size = 1;
  // Tresca friction (friction.hpp) in these variables, else n_directions 0 and the rest empty:
  // the term Σ_i radius_i ‖v_T,i − offset_i‖ joins the energy, v_T,i being the variables
  // tangential[i·n_directions + k] of contact row i (its tangential rows of T). Only the kept
  // hierarchy's pdas solves it (bound_pdas.hpp).
  int n_directions = 0;
  std::vector<int> tangential;  // m · n_directions; −1 for a row of T without a free DOF
  Eigen::VectorXd offset;       // m · n_directions: T u_prev
  Eigen::VectorXd radius;       // m: the discs' radii ≥ 0
  // A warm start (SolveOptions::initial), or empty: the multipliers whose states the loop starts
  // from (a bound active where λ_N > 0; a row sticking where ‖λ_T‖ < r, else slipping along λ_T).
  Eigen::VectorXd start_lambda, start_lambda_t;
};

struct BoundQpOptions {
  // "pdas": primal-dual active set (semismooth Newton), each step one KSP solve (CG + GAMG) on
  // the full-size matrix with the active rows and columns replaced by the identity.
  // "tao": a TAO bound-constrained method (-tao_type, TAOBNLS unless the options say otherwise).
  std::string method = "pdas";
  double tol = 1e-8;
  int max_iterations = 10000;
  std::string petsc_options;
  // pdas: inexact steps (looser KSP solves while the active set still changes, the final
  // steps at the inner rule); false solves every step at the inner rule.
  bool inexact = true;
  // pdas, kept hierarchy: a loose step's CG reduces its residual by this factor, in (0, 1).
  double loose_reduction = 0.1;
  // pdas: keep a step's preconditioner for the later steps until a solve with it needs more
  // than 200 CG iterations, or fails (false: every step set up afresh, the default). Much
  // faster in 3D, where the set-ups are the cost; off by default because the path of the
  // active set then depends on round-off (a scene in other units can take other steps).
  bool reuse_preconditioner = false;
  // pdas: one multigrid hierarchy for the whole solve, kept across the active-set steps with
  // its coarse operators following the fixed rows (bound_pdas.hpp; the default). false: the
  // loop above, a set-up per step (or per rebuild with reuse_preconditioner).
  bool kept_hierarchy = true;
  bool p1_start = true;  // kept hierarchy, quadratic elements: solve the P1 contact problem first
  bool verbose = false;
  // The relative KKT residual of an iterate in the caller's terms (v and μ on every rank):
  // the loop stops when it is ≤ tol. Stationarity holds to the inner tolerance by construction.
  std::function<double(const Eigen::VectorXd& v, const Eigen::VectorXd& mu)> residual;
  std::function<void(int k, const Eigen::VectorXd& v, const Eigen::VectorXd& mu)> observer;  // may be empty
  // With friction: the residual of v, μ and the tangential multipliers λ_T (m · n_directions),
  // in place of `residual`.
  std::function<double(const Eigen::VectorXd& v, const Eigen::VectorXd& mu, const Eigen::VectorXd& lambda_t)>
      friction_residual;
};

struct BoundQpResult {
  Status status = Status::NumericalError;
  std::string message;
  Eigen::VectorXd v, mu;          // on every rank; μ has one entry per bounded component, ≥ 0
  Eigen::VectorXd lambda_t;       // with friction: the tangential multipliers (m · n_directions), on every rank
  long long stick = 0, slip = 0;  // with friction: contact rows sticking, and slipping with a friction force
  int iterations = 0;             // outer: active-set steps, or TAO's iterations
  long long krylov_iterations = 0;
  long long linear_solves = 0;
  int preconditioner_setups = 0;  // pdas: KSP set-ups of the preconditioner
  int active = 0;                 // bounds active at the end
  double residual = 0;            // the caller's residual at the end
  double setup_seconds = 0;       // the matrix into PETSc
  double iterate_seconds = 0;     // the outer loop
  std::string method;             // what ran, e.g. "pdas, cg + gamg, 3 near-null modes"
  // Memory per rank, the largest over the ranks (MatGetInfo): A's PETSc storage, and the most
  // that A, its working copy and the multigrid hierarchy (coarse operators, interpolations)
  // held at once.
  double matrix_bytes = 0;
  double petsc_bytes = 0;
  std::vector<std::string> warnings;
  // Kept hierarchy: a solver of A with that hierarchy (no second set-up), in these variables;
  // null otherwise. Its statistics: the hierarchy's set-up time and the solves after the loop.
  std::shared_ptr<const LinearSolver> solver_of_A;
  double pc_setup_seconds = 0;  // the preconditioner's set-up (in setup_seconds' sibling iterate_seconds)
  int p1_steps = 0;             // active-set steps of the P1 start (0: none)
  long long p1_krylov_iterations = 0;
  std::string multigrid;  // levels, grid and operator complexity of the hierarchy
};

// Successive solves of one A whose b, bounds, friction radii and offsets change (Coulomb's
// Tresca solves, and the load steps of a path: petsc_backend.cpp carries the chain from one
// step's solve to the next in its solver of K), with the same chain passed to each: the first
// puts A into PETSc and sets up its hierarchy; each later one keeps both (no set-up:
// preconditioner_setups 0), takes its own b (problem.b) and bounds, and starts from the last
// answer and active set (bound_pdas.hpp's WarmStart). A, the bounded rows and the layout must
// not change along a chain; a later solve needs no A (problem.A may be empty). The method must
// be pdas with the kept hierarchy.
struct BoundQpChain {
  std::shared_ptr<void> links;  // petsc_bound_qp.cpp's: A in PETSc and the last solve; null before the first
};

// Never throws on a numerical failure (status and message say it); InputError for bad PETSc
// options or an unknown method. Collective: every rank calls it with the same problem (or its
// share of A). Takes the problem by value and frees its Eigen A once PETSc holds the matrix:
// at 1e6 DOFs that copy is a gigabyte the iteration does not need.
BoundQpResult solve_bound_qp_petsc(BoundQp problem, const BoundQpOptions& options, BoundQpChain* chain = nullptr);

}  // namespace contactqp::detail
