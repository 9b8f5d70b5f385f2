// The bound-constrained QP of the petsc backend solved by PETSc (petsc_bound_qp.hpp).
//
// pdas (the default): the primal-dual active-set method, a semismooth Newton method on
// μ = max(0, μ + c (v − upper)). Each step fixes the active bounds (v_i = upper_i) and solves the
// rest with KSP on the full-size matrix whose active rows and columns are replaced by the
// identity (MatZeroRowsColumns). Keeping the full size keeps the rigid-body near-null space
// meaningful for GAMG; a reduced matrix (MatCreateSubMatrix of the free rows, what TAO's
// active-set methods do) loses it. docs/petsc-measurements.md has the measurements behind the choice.
//
// tao: TAO's bound-constrained methods (TAOBNLS unless -tao_type says otherwise) on the same
// bound form, kept as the alternative the measurements compare against.
#include "petsc_bound_qp.hpp"

#include <petscksp.h>
#include <petsctao.h>

#include <Eigen/QR>

#include <algorithm>
#include <climits>
#include <cmath>
#include <set>
#include <sstream>

#include "bound_pdas.hpp"
#include "coarse_level.hpp"
#include "contactqp/processes.hpp"
#include "contactqp/timer.hpp"
#include "ksp_helpers.hpp"
#include "petsc_matrix.hpp"
#include "petsc_runtime.hpp"

namespace contactqp::detail {
namespace {

// The inner stopping rule and the round-off floor are those of ksp_helpers.hpp.
// Inexact steps (pdas): while the active set is still changing, a step's KSP stops at this
// fraction of the previous step's relative KKT residual (times the same force scale), never
// below the final rule; the first step, whose only use is a first active set, at 1e-2 of F.
// The stopping test is trusted only after a solve to the final rule.
constexpr double kLooseFraction = 1e-2;
// A kept preconditioner (pdas) is set up afresh after a solve that needed more CG iterations
// than this: a fresh GAMG takes 20–40 for ten digits on the shipped scenes, and a kept one on
// hertz-sphere-large.json 166 over all its 14 steps.
constexpr PetscInt kRebuildIterations = 200;

struct PetscFailure {
  std::string message;
};

void check_bound_qp(PetscErrorCode code, const char* what) {
  if (code) throw PetscFailure{std::string(what) + ": " + error_text(code)};
}

// The PETSc objects of one solve, released together (under the caller's lock).
struct Work {
  Mat A = nullptr, W = nullptr;
  KSP ksp = nullptr;
  Tao tao = nullptr;
  Vec x = nullptr, rhs = nullptr, r = nullptr, b = nullptr, x_all = nullptr, lower = nullptr, upper = nullptr;
  VecScatter to_all = nullptr;
  MatNullSpace modes = nullptr;
  void* default_test = nullptr;
  PetscInt first = 0, end = 0;  // the rows this rank owns
  RowOrder order;               // the variables' rows in the distributed matrix
  int n = 0;
  double target = 0;  // the absolute residual the current KSP solve stops at
  double A_norm = 0;
  bool options_error = false;
  double petsc_bytes = 0;  // the most that A, its working copy and the preconditioner held at once

  ~Work() {
    if (petsc_finalized()) return;
    for (Vec* v : {&x, &rhs, &r, &b, &x_all, &lower, &upper})
      if (*v) VecDestroy(v);
    if (to_all) VecScatterDestroy(&to_all);
    if (modes) MatNullSpaceDestroy(&modes);
    if (ksp) KSPDestroy(&ksp);
    if (tao) TaoDestroy(&tao);
    if (W) MatDestroy(&W);
    if (A) MatDestroy(&A);
    if (default_test) KSPConvergedDefaultDestroy(default_test);
  }

  // The whole of a distributed vector on every rank.
  Eigen::VectorXd gather(Vec v) { return gather_whole(to_all, v, x_all, order, n); }
  // The rows this rank owns of a vector every rank holds whole.
  void set(Vec v, const Eigen::VectorXd& full) {
    PetscScalar* local = nullptr;
    VecGetArray(v, &local);
    order.to_local(full, first, end, local);
    VecRestoreArray(v, &local);
  }

  // KSPConvergedDefault (divergence, -ksp_max_it, a user's -ksp_rtol), then the inner rule.
  static PetscErrorCode converged(KSP ksp, PetscInt it, PetscReal rnorm, KSPConvergedReason* reason, void* context) {
    Work& work = *static_cast<Work*>(context);
    PetscCall(KSPConvergedDefault(ksp, it, rnorm, reason, work.default_test));
    return inner_stopping_rule(ksp, rnorm, work.target, work.A_norm, reason);
  }

  // TAO's objective ½ xᵀAx − bᵀx and gradient Ax − b.
  static PetscErrorCode objective(Tao, Vec x, PetscReal* value, Vec gradient, void* context) {
    Work& work = *static_cast<Work*>(context);
    PetscScalar xAx = 0, bx = 0;
    PetscCall(MatMult(work.A, x, gradient));
    PetscCall(VecDot(x, gradient, &xAx));
    PetscCall(VecDot(work.b, x, &bx));
    *value = 0.5 * xAx - bx;
    PetscCall(VecAXPY(gradient, -1.0, work.b));
    return 0;
  }
  static PetscErrorCode hessian(Tao, Vec, Mat, Mat, void*) { return 0; }  // A, constant
};

void assemble(Work& work, const BoundQp& problem) {
  check_bound_qp(owned_rows(work.n, &work.first, &work.end), "PetscSplitOwnership");
  const PetscInt local_rows = work.end - work.first;
  check_bound_qp(MatCreate(PETSC_COMM_WORLD, &work.A), "MatCreate");
  check_bound_qp(MatSetSizes(work.A, local_rows, local_rows, work.n, work.n), "MatSetSizes");
  check_bound_qp(MatSetType(work.A, MATAIJ), "MatSetType");
  const char* step = "";
  check_bound_qp(fill_matrix(work.A, problem.A, problem.A_is_rank_share, work.order, work.first, work.end, &step),
                 step);
  MatNorm(work.A, NORM_INFINITY, &work.A_norm);
  MatSetOption(work.A, MAT_SYMMETRIC, PETSC_TRUE);
  MatSetOption(work.A, MAT_SPD, PETSC_TRUE);

  // The near-null space, orthonormalised, for GAMG.
  const Eigen::MatrixXd& modes = problem.near_null_space;
  if (modes.cols() > 0 && modes.rows() == work.n) {
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(modes);
    const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(work.n, modes.cols());
    std::vector<Vec> vectors(modes.cols());
    for (Eigen::Index k = 0; k < modes.cols(); ++k) {
      MatCreateVecs(work.A, &vectors[k], nullptr);
      work.set(vectors[k], Q.col(k));
    }
    const PetscErrorCode code = MatNullSpaceCreate(PETSC_COMM_WORLD, PETSC_FALSE, static_cast<PetscInt>(vectors.size()),
                                                   vectors.data(), &work.modes);
    for (Vec& v : vectors) VecDestroy(&v);
    check_bound_qp(code, "MatNullSpaceCreate");
    check_bound_qp(MatSetNearNullSpace(work.A, work.modes), "MatSetNearNullSpace");
  }
  MatCreateVecs(work.A, &work.x, &work.rhs);
  VecDuplicate(work.x, &work.r);
  VecDuplicate(work.x, &work.b);
  work.set(work.b, problem.b);
  check_bound_qp(VecScatterCreateToAll(work.x, &work.to_all, &work.x_all), "VecScatterCreateToAll");
}

// A, its working copy W and the multigrid hierarchy on this rank: the coarse operators and the
// interpolations (GAMG's restriction is the transpose of the same matrix); the coarsest
// level's LU is a few hundred rows and left out. Other preconditioners: A and W only.
double petsc_bytes(Work& work) {
  double bytes = matrix_bytes(work.A) + (work.W ? matrix_bytes(work.W) : 0.0);
  if (!work.ksp) return bytes;
  PC pc = nullptr;
  KSPGetPC(work.ksp, &pc);
  PetscBool multigrid = PETSC_FALSE;
  PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(pc), &multigrid, PCGAMG, PCMG, "");
  PetscInt levels = 0;
  if (!multigrid || PCMGGetLevels(pc, &levels)) return bytes;
  for (PetscInt level = 0; level < levels; ++level) {
    KSP smoother = nullptr;
    Mat op = nullptr;
    if (level + 1 < levels && !PCMGGetSmoother(pc, level, &smoother) && !KSPGetOperators(smoother, &op, nullptr) && op)
      bytes += matrix_bytes(op);
    Mat interpolation = nullptr;
    if (level > 0 && !PCMGGetInterpolation(pc, level, &interpolation) && interpolation)
      bytes += matrix_bytes(interpolation);
  }
  return bytes;
}

double inf_norm(const Eigen::VectorXd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

// The primal-dual active-set loop.
void solve_pdas(Work& work, const BoundQp& problem, const BoundQpOptions& options, BoundQpResult& result) {
  const int m = static_cast<int>(problem.bounded.size());
  check_bound_qp(MatDuplicate(work.A, MAT_COPY_VALUES, &work.W), "MatDuplicate");
  check_bound_qp(KSPCreate(PETSC_COMM_WORLD, &work.ksp), "KSPCreate");
  KSPSetType(work.ksp, KSPCG);
  PC pc = nullptr;
  KSPGetPC(work.ksp, &pc);
  PCSetType(pc, PCGAMG);
  // GAMG set up afresh for each active set: reusing the first step's interpolation (PETSc's
  // default) reuses its Chebyshev eigenvalue estimates too, which do not hold for the matrix
  // with fixed rows (KSP_DIVERGED_INDEFINITE_PC on disc-in-vgroove). -pc_gamg_reuse_interpolation
  // overrides it (docs/petsc-measurements.md measures both).
  PCGAMGSetReuseInterpolation(pc, PETSC_FALSE);
  KSPSetNormType(work.ksp, KSP_NORM_UNPRECONDITIONED);
  KSPSetTolerances(work.ksp, 0.0, 0.0, PETSC_DEFAULT, kMaxKrylovIterations);
  KSPConvergedDefaultCreate(&work.default_test);
  KSPSetConvergenceTest(work.ksp, Work::converged, &work, nullptr);
  KSPSetOperators(work.ksp, work.W, work.W);
  if (PetscErrorCode code = KSPSetFromOptions(work.ksp)) {
    work.options_error = true;
    check_bound_qp(code, "KSPSetFromOptions");
  }
  KSPSetInitialGuessNonzero(work.ksp, PETSC_TRUE);

  // c_i = A_ii: the semismooth Newton step's weight, in the units that make μ + c (v − upper)
  // a force.
  check_bound_qp(MatGetDiagonal(work.A, work.r), "MatGetDiagonal");
  const Eigen::VectorXd diagonal = work.gather(work.r);
  const double b_norm = inf_norm(problem.b);
  // The value on the diagonal of a fixed row: the mean of A's diagonal there, so that the
  // fixed rows do not stretch the spectrum the smoothers of GAMG are tuned to (a 1 among
  // entries of another size gave KSP_DIVERGED_INDEFINITE_PC on disc-in-vgroove).
  double fixed_diagonal = 0;
  for (int i = 0; i < m; ++i) fixed_diagonal += diagonal[problem.bounded[i]] / m;
  if (!(fixed_diagonal > 0)) fixed_diagonal = 1;

  Eigen::VectorXd v = Eigen::VectorXd::Zero(work.n), mu = Eigen::VectorXd::Zero(m);
  std::vector<char> active(m, 0);  // the first step solves without bounds
  std::set<std::vector<char>> seen;
  // Loose solves until a step's active set repeats or passes the test; then final-rule solves
  // only (a loose step that passes is solved again from where it is).
  bool tight = false, rebuild = false;
  double previous_residual = 1.0;
  for (int k = 1;; ++k) {
    seen.insert(active);
    // The system of this active set: v_i = upper_i on the active bounds, A v = b on the rest.
    check_bound_qp(MatCopy(work.A, work.W, SAME_NONZERO_PATTERN), "MatCopy");
    std::vector<PetscInt> rows;
    Eigen::VectorXd guess = v;
    for (int i = 0; i < m; ++i)
      if (active[i]) {
        guess[problem.bounded[i]] = problem.upper[i];
        const PetscInt row = work.order.row(problem.bounded[i]);
        if (row >= work.first && row < work.end) rows.push_back(row);
      }
    work.set(work.x, guess);
    check_bound_qp(VecCopy(work.b, work.rhs), "VecCopy");
    check_bound_qp(
        MatZeroRowsColumns(work.W, static_cast<PetscInt>(rows.size()), rows.data(), fixed_diagonal, work.x, work.rhs),
        "MatZeroRowsColumns");
    if (work.modes) check_bound_qp(MatSetNearNullSpace(work.W, work.modes), "MatSetNearNullSpace");
    check_bound_qp(KSPSetOperators(work.ksp, work.W, work.W), "KSPSetOperators");
    // The preconditioner of an earlier step's matrix serves the later ones (reuse_preconditioner):
    // they differ from it only in the fixed rows, and CG converges with any SPD preconditioner.
    // It is set up afresh after a solve with it that needed more than kRebuildIterations, or to
    // repeat a solve that failed with it. A rule by counts, not by time: the same problem takes
    // the same steps on every run, in any units.
    const bool keep = options.reuse_preconditioner && result.preconditioner_setups > 0 && !rebuild;
    check_bound_qp(KSPSetReusePreconditioner(work.ksp, keep ? PETSC_TRUE : PETSC_FALSE), "KSPSetReusePreconditioner");
    if (!keep) {
      ++result.preconditioner_setups;
      check_bound_qp(KSPSetUp(work.ksp), "KSPSetUp");
    }
    const double force = std::max(b_norm, inf_norm(mu));
    const double final_target = force > 0 ? kInnerFraction * options.tol * force : kInnerFraction * options.tol;
    const bool solved_tight = tight || !options.inexact;
    work.target = solved_tight ? final_target : std::max(final_target, kLooseFraction * previous_residual * force);
    check_bound_qp(KSPSolve(work.ksp, work.rhs, work.x), "KSPSolve");
    work.petsc_bytes = std::max(work.petsc_bytes, petsc_bytes(work));
    PetscInt iterations = 0;
    KSPGetIterationNumber(work.ksp, &iterations);
    result.krylov_iterations += iterations;
    ++result.linear_solves;
    result.iterations = k;
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    KSPGetConvergedReason(work.ksp, &reason);
    // PCSetUp is collective: the ranks decide together (the counts are global anyway).
    int mine = keep && (reason < 0 || iterations > kRebuildIterations), any = 0;
    MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
    rebuild = any != 0;
    if (reason < 0 && keep && k < options.max_iterations) continue;  // the same step, set up afresh
    if (reason < 0) {
      result.status = Status::NumericalError;
      result.message = reason_text(work.ksp, iterations, work.target);
      break;
    }

    // μ = b − A v on the active bounds (the force that holds them), 0 on the others.
    v = work.gather(work.x);
    check_bound_qp(MatMult(work.A, work.x, work.r), "MatMult");
    const Eigen::VectorXd Av = work.gather(work.r);
    for (int i = 0; i < m; ++i) mu[i] = active[i] ? problem.b[problem.bounded[i]] - Av[problem.bounded[i]] : 0.0;
    if (!v.allFinite() || !mu.allFinite()) {
      result.status = Status::NumericalError;
      result.message = "the PETSc KSP returned a solution that is not finite";
      break;
    }
    if (options.observer) options.observer(k, v, mu.cwiseMax(0.0));
    result.residual = options.residual(v, mu);
    previous_residual = std::min(1.0, result.residual);
    std::vector<char> next(m, 0);
    for (int i = 0; i < m; ++i)
      next[i] = mu[i] + diagonal[problem.bounded[i]] * (v[problem.bounded[i]] - problem.upper[i]) > 0;
    if (!solved_tight && (result.residual <= options.tol || next == active || seen.count(next))) {
      // Settled, or cycling, at a loose solve: the same active set again at the final rule.
      tight = true;
      seen.clear();
      if (k >= options.max_iterations) {
        result.status = Status::MaxIterations;
        result.message =
            "stopped after " + std::to_string(k) + " active-set steps with residual " + number_text(result.residual);
        break;
      }
      continue;
    }
    if (result.residual <= options.tol) {
      result.status = Status::Converged;
      break;
    }
    if (next == active) {
      result.status = Status::NumericalError;
      result.message = "the active set settled with residual " + number_text(result.residual) +
                       " above tol: the inner KSP solves are not accurate enough (a smaller -ksp_rtol may help)";
      break;
    }
    if (seen.count(next)) {
      result.status = Status::NumericalError;
      result.message = "the active-set steps cycled at residual " + number_text(result.residual) +
                       " (try --backend-option method=tao)";
      break;
    }
    if (k >= options.max_iterations) {
      result.status = Status::MaxIterations;
      result.message =
          "stopped after " + std::to_string(k) + " active-set steps with residual " + number_text(result.residual);
      break;
    }
    active = std::move(next);
  }
  result.v = v;
  result.mu = mu.cwiseMax(0.0);
  result.active = static_cast<int>(std::count(active.begin(), active.end(), 1));
  KSPType type = nullptr;
  PCType pc_type = nullptr;
  KSPGetType(work.ksp, &type);
  KSPGetPC(work.ksp, &pc);
  PCGetType(pc, &pc_type);
  result.method = std::string("pdas, ") + (type ? type : "?") + " + " + (pc_type ? pc_type : "?") +
                  (work.modes ? ", " + std::to_string(problem.near_null_space.cols()) + " near-null modes" : "");
}

// The kept hierarchy's solver of A (bound_pdas.hpp) behind the LinearSolver interface, on
// vectors every rank holds whole: certify()'s θ solves with the contact solve's hierarchy.
class HierarchySolver final : public LinearSolver {
 public:
  struct State {
    std::shared_ptr<SolverOfA> solver;
    Vec rhs = nullptr, x = nullptr, x_all = nullptr;
    VecScatter to_all = nullptr;
    RowOrder order;
    PetscInt first = 0, end = 0;
    int n = 0;
    bool ok = true;
    std::string message, method;
    double setup_seconds = 0;
    long long solves = 0;

    ~State() {
      if (petsc_finalized()) return;
      std::lock_guard<std::mutex> lock(petsc_mutex());
      for (Vec* v : {&rhs, &x, &x_all})
        if (*v) VecDestroy(v);
      if (to_all) VecScatterDestroy(&to_all);
      solver.reset();  // its KSP and hierarchy, under the lock
    }
  };
  HierarchySolver(std::shared_ptr<State> state, double scale) : state_(std::move(state)), scale_(scale) {}

  bool ok() const override {
    std::lock_guard<std::mutex> lock(petsc_mutex());
    return state_->ok;
  }
  const std::string& message() const override { return state_->message; }
  int size() const override { return state_->n; }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const override {
    State& s = *state_;
    std::lock_guard<std::mutex> lock(petsc_mutex());
    if (!s.ok || b.size() != s.n) return Eigen::VectorXd::Zero(b.size());
    const double force = inf_norm(b);
    if (force == 0) return Eigen::VectorXd::Zero(s.n);
    PetscScalar* local = nullptr;
    VecGetArray(s.rhs, &local);
    s.order.to_local(b, s.first, s.end, local);
    VecRestoreArray(s.rhs, &local);
    ++s.solves;
    if (!s.solver->solve(s.rhs, s.x, force)) {
      s.ok = false;
      s.message = "the PETSc KSP with the contact solve's hierarchy did not converge on a solve with A";
      return Eigen::VectorXd::Zero(s.n);
    }
    return gather_whole(s.to_all, s.x, s.x_all, s.order, s.n) / scale_;
  }
  LinearSolverStatistics statistics() const override {
    std::lock_guard<std::mutex> lock(petsc_mutex());
    LinearSolverStatistics statistics;
    statistics.name = "petsc";
    statistics.method = state_->method;
    statistics.setup_seconds = state_->setup_seconds;
    statistics.solves = state_->solves;
    statistics.iterations = state_->solver->iterations();
    return statistics;
  }

 protected:
  std::shared_ptr<const LinearSolver> scaled_solver(double c) const override {
    return std::make_shared<HierarchySolver>(state_, scale_ * c);
  }

 private:
  std::shared_ptr<State> state_;
  double scale_ = 1.0;
};

// The primal-dual active-set loop with one hierarchy kept across its steps (bound_pdas.hpp),
// on this rank's rows; v and μ whole on every rank for the caller's residual and the result.
// What a chain of solves keeps (BoundQpChain): A in PETSc, and the last solve's hierarchy,
// answer and active set, where the next starts.
struct ChainLinks {
  std::shared_ptr<Work> work;
  BoundPdasResult last;
};

void solve_kept(Work& work, const BoundQp& problem, const BoundQpOptions& options, BoundQpResult& result,
                ChainLinks* links) {
  const int m = static_cast<int>(problem.bounded.size());
  PetscBoundQp qp;
  qp.A = work.A;
  qp.b = work.b;
  std::vector<std::pair<PetscInt, int>> mine;  // this rank's bounds: row, index
  for (int i = 0; i < m; ++i) {
    const PetscInt row = work.order.row(problem.bounded[i]);
    if (row >= work.first && row < work.end) mine.emplace_back(row, i);
  }
  std::sort(mine.begin(), mine.end());
  const bool warm = problem.start_lambda.size() == m;
  for (const auto& [row, i] : mine) {
    qp.bounded.push_back(row);
    qp.upper.push_back(problem.upper[i]);
    if (warm) qp.start_active.push_back(problem.start_lambda[i] > 0);
  }
  // Friction: this rank's contact rows, those whose first tangential variable it owns (a row's
  // variables are its node's DOFs, or one group's, which a rank holds together).
  const int nd = problem.n_directions;
  std::vector<int> mine_friction;  // contact rows, by their first tangential variable's row
  if (nd > 0) {
    std::vector<std::pair<PetscInt, int>> rows;
    for (int i = 0; i < m; ++i) {
      int variable = -1;  // its first direction with a variable (none: λ_T = 0, nothing to solve)
      for (int d = 0; d < nd && variable < 0; ++d) variable = problem.tangential[static_cast<std::size_t>(i) * nd + d];
      if (variable < 0) continue;
      const PetscInt row = work.order.row(variable);
      if (row >= work.first && row < work.end) rows.emplace_back(row, i);
    }
    std::sort(rows.begin(), rows.end());
    qp.n_directions = nd;
    for (const auto& [row, i] : rows) {
      mine_friction.push_back(i);
      for (int d = 0; d < nd; ++d) {
        const int variable = problem.tangential[static_cast<std::size_t>(i) * nd + d];
        const PetscInt own = variable < 0 ? -1 : work.order.row(variable);
        if (variable >= 0 && (own < work.first || own >= work.end))
          throw PetscFailure{"a contact row's tangential variables are on two ranks; run friction on one process"};
        qp.tangential.push_back(own);
        qp.offset.push_back(problem.offset[i * nd + d]);
      }
      qp.radius.push_back(problem.radius[i]);
      if (problem.start_lambda_t.size() == static_cast<Eigen::Index>(m) * nd) {
        const Eigen::VectorXd t = problem.start_lambda_t.segment(static_cast<Eigen::Index>(i) * nd, nd);
        const double norm = t.norm();
        qp.start_stick.push_back(problem.radius[i] > 0 && norm < problem.radius[i]);
        for (int d = 0; d < nd; ++d) qp.start_direction.push_back(norm > 0 ? t[d] / norm : 0.0);
      }
    }
  }
  // A later solve of a chain keeps the hierarchy: no P1 level to build again.
  const bool chained = links && links->last.solver_of_A;
  CoarseLevel coarse;
  if (problem.coarse_interpolation.cols() > 0 && !chained) {
    CoarseLevelInput input;
    input.interpolation = &problem.coarse_interpolation;
    input.modes = &problem.coarse_near_null_space;
    input.column_vertex = &problem.coarse_vertex;
    input.vertex_row = &problem.coarse_row;
    input.block_size = problem.coarse_block_size;
    check_bound_qp(coarse.create(input, work.order, work.first, work.end, work.A), "the P1 level");
    qp.coarse_interpolation = coarse.interpolation();
    qp.coarse_modes = coarse.modes();
    for (const auto& [row, i] : mine)
      qp.coarse_bounded.push_back(problem.coarse_bounded[i] >= 0 ? coarse.column(problem.coarse_bounded[i]) : -1);
  }
  // μ of this rank's bounds into the whole μ, on every rank.
  auto whole_mu = [&](const std::vector<double>& mu_mine) {
    Eigen::VectorXd mu = Eigen::VectorXd::Zero(m);
    for (std::size_t k = 0; k < mine.size(); ++k) mu[mine[k].second] = mu_mine[k];
    MPI_Allreduce(MPI_IN_PLACE, mu.data(), m, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    return mu;
  };
  // λ_T of this rank's contact rows into the whole λ_T, on every rank.
  auto whole_lambda_t = [&](const std::vector<double>& mine_t) {
    Eigen::VectorXd lambda_t = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(m) * nd);
    for (std::size_t k = 0; k < mine_friction.size(); ++k)
      for (int d = 0; d < nd; ++d) lambda_t[mine_friction[k] * nd + d] = mine_t[k * nd + d];
    MPI_Allreduce(MPI_IN_PLACE, lambda_t.data(), static_cast<int>(lambda_t.size()), MPI_DOUBLE, MPI_SUM,
                  PETSC_COMM_WORLD);
    return lambda_t;
  };
  BoundPdasOptions settings;
  settings.tol = options.tol;
  settings.max_iterations = options.max_iterations;
  settings.inexact = options.inexact;
  settings.loose_reduction = options.loose_reduction;
  settings.p1_start = options.p1_start;
  int step = 0;
  settings.residual = [&](Vec v, const std::vector<double>& mu_mine) {
    const Eigen::VectorXd whole = work.gather(v), mu = whole_mu(mu_mine);
    if (options.observer) options.observer(++step, whole, mu.cwiseMax(0.0));
    return options.residual(whole, mu);
  };
  if (nd > 0)
    settings.friction_residual = [&](Vec v, const std::vector<double>& mu_mine, const std::vector<double>& t_mine) {
      const Eigen::VectorXd whole = work.gather(v), mu = whole_mu(mu_mine);
      if (options.observer) options.observer(++step, whole, mu.cwiseMax(0.0));
      return options.friction_residual(whole, mu, whole_lambda_t(t_mine));
    };
  BoundPdasResult solved;
  bool options_error = false;
  WarmStart start;
  if (chained) {
    start.solver_of_A = links->last.solver_of_A;
    start.v = links->last.v;
    start.active_bounds = links->last.active_bounds;
    start.multigrid = links->last.multigrid;
  }
  if (PetscErrorCode code = solve_bound_pdas(qp, settings, &solved, &options_error, chained ? &start : nullptr)) {
    work.options_error = options_error;
    check_bound_qp(code, options_error ? "the preconditioner's set-up" : "the active-set loop");
  }
  result.status = solved.status;
  result.message = solved.message;
  result.v = work.gather(solved.v);
  result.mu = whole_mu(solved.mu).cwiseMax(0.0);
  if (nd > 0) {
    result.lambda_t = whole_lambda_t(solved.lambda_t);
    result.stick = solved.stick;
    result.slip = solved.slip;
  }
  result.iterations = solved.iterations;
  result.krylov_iterations = solved.krylov_iterations;
  result.linear_solves = solved.linear_solves;
  result.preconditioner_setups = solved.preconditioner_setups;
  result.active = static_cast<int>(solved.active);
  result.residual = solved.residual;
  result.method = solved.method;
  result.pc_setup_seconds = solved.setup_seconds;
  result.p1_steps = solved.p1_steps;
  result.p1_krylov_iterations = solved.p1_krylov_iterations;
  std::ostringstream multigrid;
  multigrid.precision(3);
  multigrid << solved.multigrid.levels << " levels, grid complexity " << solved.multigrid.grid_complexity
            << ", operator complexity " << solved.multigrid.operator_complexity;
  result.multigrid = multigrid.str();
  work.petsc_bytes = matrix_bytes(work.A) + solved.multigrid.bytes;

  auto state = std::make_shared<HierarchySolver::State>();
  state->solver = solved.solver_of_A;
  state->order = work.order;
  state->first = work.first;
  state->end = work.end;
  state->n = work.n;
  state->method = "cg + " + solved.multigrid.method + " (the contact solve's hierarchy)";
  check_bound_qp(MatCreateVecs(work.A, &state->x, &state->rhs), "MatCreateVecs");
  check_bound_qp(VecScatterCreateToAll(state->x, &state->to_all, &state->x_all), "VecScatterCreateToAll");
  result.solver_of_A = std::make_shared<HierarchySolver>(state, 1.0);
  if (links) links->last = std::move(solved);
}

// TAO's bound-constrained methods on the same problem.
void solve_tao(Work& work, const BoundQp& problem, const BoundQpOptions& options, BoundQpResult& result) {
  const int m = static_cast<int>(problem.bounded.size());
  Eigen::VectorXd lower = Eigen::VectorXd::Constant(work.n, PETSC_NINFINITY);
  Eigen::VectorXd upper = Eigen::VectorXd::Constant(work.n, PETSC_INFINITY);
  for (int i = 0; i < m; ++i) upper[problem.bounded[i]] = problem.upper[i];
  VecDuplicate(work.x, &work.lower);
  VecDuplicate(work.x, &work.upper);
  work.set(work.lower, lower);
  work.set(work.upper, upper);
  work.set(work.x, Eigen::VectorXd(upper.cwiseMin(0.0)));

  check_bound_qp(TaoCreate(PETSC_COMM_WORLD, &work.tao), "TaoCreate");
  TaoSetType(work.tao, TAOBNLS);
  TaoSetSolution(work.tao, work.x);
  TaoSetVariableBounds(work.tao, work.lower, work.upper);
  TaoSetObjectiveAndGradient(work.tao, nullptr, Work::objective, &work);
  TaoSetHessian(work.tao, work.A, work.A, Work::hessian, &work);
  const double gatol = kInnerFraction * options.tol * std::max(inf_norm(problem.b), 1e-300);
  TaoSetTolerances(work.tao, gatol, 0.0, 0.0);
  TaoSetMaximumIterations(work.tao, options.max_iterations);
  if (PetscErrorCode code = TaoSetFromOptions(work.tao)) {
    work.options_error = true;
    check_bound_qp(code, "TaoSetFromOptions");
  }
  check_bound_qp(TaoSolve(work.tao), "TaoSolve");
  work.petsc_bytes = petsc_bytes(work);  // A (TAO's own reduced matrices are not counted)
  TaoConvergedReason reason = TAO_CONTINUE_ITERATING;
  TaoGetConvergedReason(work.tao, &reason);
  PetscInt iterations = 0, linear = 0;
  TaoGetIterationNumber(work.tao, &iterations);
  TaoGetLinearSolveIterations(work.tao, &linear);
  result.iterations = static_cast<int>(iterations);
  result.krylov_iterations = linear;

  Vec solution = nullptr;
  TaoGetSolution(work.tao, &solution);
  result.v = work.gather(solution);
  check_bound_qp(MatMult(work.A, solution, work.r), "MatMult");
  const Eigen::VectorXd Av = work.gather(work.r);
  Eigen::VectorXd mu(m);
  for (int i = 0; i < m; ++i) mu[i] = problem.b[problem.bounded[i]] - Av[problem.bounded[i]];
  result.mu = mu.cwiseMax(0.0);
  result.active = static_cast<int>((result.mu.array() > 0).count());
  result.residual = options.residual(result.v, mu);
  TaoType type = nullptr;
  TaoGetType(work.tao, &type);
  result.method = std::string("tao ") + (type ? type : "?");
  if (!result.v.allFinite()) {
    result.status = Status::NumericalError;
    result.message = "TAO returned a solution that is not finite";
  } else if (result.residual <= options.tol) {
    result.status = Status::Converged;
  } else {
    result.status = reason == TAO_DIVERGED_MAXITS ? Status::MaxIterations : Status::NumericalError;
    result.message = std::string("TAO stopped (") + TaoConvergedReasons[reason] + ") at residual " +
                     number_text(result.residual) + " above tol";
  }
}

}  // namespace

BoundQpResult solve_bound_qp_petsc(BoundQp problem, const BoundQpOptions& options, BoundQpChain* chain) {
  if (options.method != "pdas" && options.method != "tao")
    throw InputError("method", "= \"" + options.method + "\": not a method of the petsc backend; valid: pdas, tao");
  BoundQpResult result;
  bool options_error = false;
  const auto* chained = chain ? static_cast<const ChainLinks*>(chain->links.get()) : nullptr;
  const int n = chained ? chained->work->n : static_cast<int>(problem.A.rows());
  {
    std::lock_guard<std::mutex> lock(petsc_mutex());
    PetscRuntime& runtime = PetscRuntime::instance(options.petsc_options);
    runtime.use_options(options.petsc_options);
    const long generation = runtime.generation();
    // A chain's later solve: its A in PETSc, already there.
    ChainLinks* links = chain ? static_cast<ChainLinks*>(chain->links.get()) : nullptr;
    const std::shared_ptr<Work> kept = links ? links->work : nullptr;
    const std::shared_ptr<Work> owned = kept ? kept : std::make_shared<Work>();
    Work& work = *owned;
    if (!kept) {
      work.n = n;
      work.order = RowOrder(problem.distributed_row);
    }
    std::string failure;
    // Every rank learns whether any failed and the lowest failing rank's message, by the runs'
    // one protocol (agree_on_failure(), processes.hpp), so that all take the same branch: a rank
    // that went on alone into a collective call would wait for the one that stopped.
    const auto failed_anywhere = [&failure] {
      const AgreedFailure agreed = agree_on_failure(failure.empty() ? 0 : 1, failure);
      if (agreed.status != 0 && agreed.process != 0)
        failure = agreed.error + " (on rank " + std::to_string(agreed.process) + ")";
      else if (agreed.status != 0)
        failure = agreed.error;
      return agreed.status != 0;
    };
    Stopwatch clock;
    try {
      if (!kept)
        assemble(work, problem);
      else if (problem.b.size() == work.n)  // a load step along the chain: its own b
        work.set(work.b, problem.b);
    } catch (const PetscFailure& error) {
      failure = error.message;
    }
    problem.A = Eigen::SparseMatrix<double>();  // PETSc has its own copy
    result.setup_seconds = clock.seconds();
    if (!failed_anywhere()) {
      clock.restart();
      try {
        if (problem.n_directions > 0 && !(options.method == "pdas" && options.kept_hierarchy))
          throw PetscFailure{"friction is solved by method=pdas with hierarchy=kept (the defaults) only"};
        if (chain && !(options.method == "pdas" && options.kept_hierarchy))
          throw PetscFailure{"a chain of solves keeps the hierarchy: method=pdas with hierarchy=kept only"};
        if (chain && !links) {  // the chain's first solve: what it keeps from here on
          links = new ChainLinks{owned, {}};
          chain->links = std::shared_ptr<void>(links, [](void* p) {
            const std::lock_guard<std::mutex> lock(petsc_mutex());  // PETSc objects freed one caller at a time
            delete static_cast<ChainLinks*>(p);
          });
        }
        if (options.method == "pdas" && options.kept_hierarchy)
          solve_kept(work, problem, options, result, links);
        else if (options.method == "pdas")
          solve_pdas(work, problem, options, result);
        else
          solve_tao(work, problem, options, result);
      } catch (const PetscFailure& error) {
        failure = error.message;
      }
      result.iterate_seconds = clock.seconds();
      options_error = work.options_error;
      failed_anywhere();
    }
    if (!failure.empty()) {
      result.status = Status::NumericalError;
      result.message = failure;
    } else {
      double mine[2] = {matrix_bytes(work.A), work.petsc_bytes}, largest[2] = {0, 0};
      MPI_Allreduce(mine, largest, 2, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
      result.matrix_bytes = largest[0];
      result.petsc_bytes = largest[1];
    }
    if (runtime.generation() == generation)
      for (const std::string& option : runtime.unused(options.petsc_options))
        result.warnings.push_back("PETSc option " + option + " was not used (PETSc's -options_left)");
  }
  if (options_error) throw InputError("petsc_options", "= \"" + options.petsc_options + "\": " + result.message);
  if (result.v.size() != n) result.v = Eigen::VectorXd::Zero(n);
  if (result.mu.size() != static_cast<Eigen::Index>(problem.bounded.size()))
    result.mu = Eigen::VectorXd::Zero(problem.bounded.size());
  return result;
}

}  // namespace contactqp::detail
