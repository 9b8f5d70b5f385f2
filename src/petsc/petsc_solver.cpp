// PETSc behind the LinearSolver interface: K copied into a PETSc AIJ matrix (MPIAIJ), solved by
// a KSP — CG preconditioned by GAMG with the rigid-body near-null space, unless the options
// database says otherwise; registered as the solver of LinearSolverKind::Petsc (at the end).
// docs/linear-solvers.md has the user's view: options, the inner tolerance rule, what is measured.
//
// The process-wide part (PetscRuntime): PetscInitialize once, on first use, which starts MPI
// when nobody did; PetscFinalize at exit (std::atexit), so that every way out of main(),
// exit status 2 included, ends PETSc and MPI in order.
#include "petsc_solver.hpp"

#include "coarse_level.hpp"
#include "ksp_helpers.hpp"
#include "mpi.hpp"
#include "multigrid.hpp"
#include "petsc_matrix.hpp"
#include "petsc_runtime.hpp"

#include <petscksp.h>

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <set>
#include <sstream>
#include <vector>

#include "contactqp/errors.hpp"
#include "contactqp/timer.hpp"

namespace contactqp::detail {
namespace {

class PetscSolver final : public LinearSolver {
 public:
  struct Impl;
  PetscSolver(std::shared_ptr<Impl> impl, double scale) : impl_(std::move(impl)), scale_(scale) {}

  bool ok() const override;
  const std::string& message() const override;
  int size() const override;
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const override { return solve(b, Eigen::VectorXd()); }
  Eigen::VectorXd solve(const Eigen::VectorXd& b, const Eigen::VectorXd& guess) const override;
  LinearSolverStatistics statistics() const override;
  std::vector<std::string> warnings() const override;

 protected:
  std::shared_ptr<const LinearSolver> scaled_solver(double c) const override {
    return std::make_shared<PetscSolver>(impl_, scale_ * c);
  }

 private:
  std::shared_ptr<Impl> impl_;
  double scale_ = 1.0;  // stands for scale·A: solves divide by it
};

struct PetscSolver::Impl {
  Mat A = nullptr;
  KSP ksp = nullptr;
  Vec x = nullptr, b = nullptr;
  VecScatter to_all = nullptr;  // the distributed solution onto every rank (one rank: a copy)
  Vec x_all = nullptr;
  CoarseLevel coarse;             // quadratic elements: the P1 level (coarse_level.hpp)
  Mat coarse_operator = nullptr;  // PᵀAP, when the P1 level is used
  void* default_test = nullptr;   // KSPConvergedDefault's context: the user's -ksp_rtol etc.
  int n = 0;
  PetscInt first_row = 0, end_row = 0;  // the rows this rank owns
  RowOrder order;                       // the unknowns' rows in A
  double tol = 1e-8;
  double target = 0;  // the absolute residual the current solve stops at
  double A_norm = 0;  // ‖A‖∞, for the round-off floor
  bool ok = false;
  std::string message;
  std::string options;
  std::vector<std::string> warnings;
  bool checked_unused = false;
  long generation = -1;  // of the options database at set-up
  double setup_seconds = 0;
  long long solves = 0, iterations = 0;
  std::string method;

  ~Impl() {
    if (petsc_finalized()) return;  // PETSc freed everything at finalize
    std::lock_guard<std::mutex> lock(petsc_mutex());
    if (to_all) VecScatterDestroy(&to_all);
    if (x_all) VecDestroy(&x_all);
    if (x) VecDestroy(&x);
    if (b) VecDestroy(&b);
    if (ksp) KSPDestroy(&ksp);
    if (coarse_operator) MatDestroy(&coarse_operator);
    if (A) MatDestroy(&A);
    if (default_test) KSPConvergedDefaultDestroy(default_test);
  }

  bool fail(const std::string& what, PetscErrorCode code) {
    ok = false;
    message = what + ": " + error_text(code);
    return false;
  }
  // The options database named something PETSc does not have (an unknown KSP or PC type, a
  // bad value): bad input, reported as such once the PETSc objects are released.
  bool bad_options(const std::string& what, PetscErrorCode code) {
    options_error = true;
    return fail(what, code);
  }
  bool options_error = false;
  bool preconditioned_norm = false;  // the method could not measure the true residual

  // KSPConvergedDefault first (divergence, -ksp_max_it, a user's -ksp_rtol or -ksp_atol), then
  // the inner rule on the unpreconditioned residual norm.
  static PetscErrorCode converged(KSP ksp, PetscInt it, PetscReal rnorm, KSPConvergedReason* reason, void* context) {
    Impl& impl = *static_cast<Impl*>(context);
    PetscCall(KSPConvergedDefault(ksp, it, rnorm, reason, impl.default_test));
    return inner_stopping_rule(ksp, rnorm, impl.target, impl.A_norm, reason);
  }

  bool set_up(const Eigen::SparseMatrix<double>& K, const LinearSolverOptions& options, const MatrixLayout& layout);
};

bool PetscSolver::Impl::set_up(const Eigen::SparseMatrix<double>& K, const LinearSolverOptions& settings,
                               const MatrixLayout& layout) {
  PetscErrorCode code = 0;
  // Rows are distributed by PETSc (PETSC_DECIDE); each rank sets the rows it owns from its copy
  // of K, or adds its share of K (layout.share) wherever it lands.
  if ((code = owned_rows(n, &first_row, &end_row))) return fail("PetscSplitOwnership", code);
  const PetscInt local_rows = end_row - first_row;
  if ((code = MatCreate(PETSC_COMM_WORLD, &A))) return fail("MatCreate", code);
  if ((code = MatSetSizes(A, local_rows, local_rows, n, n))) return fail("MatSetSizes", code);
  if ((code = MatSetType(A, MATMPIAIJ))) return fail("MatSetType", code);
  if ((code = MatSetFromOptions(A))) return bad_options("MatSetFromOptions", code);
  const char* step = "";
  order = RowOrder(layout.distributed_row);
  if ((code = fill_matrix(A, K, layout.share, order, first_row, end_row, &step))) return fail(step, code);
  MatNorm(A, NORM_INFINITY, &A_norm);
  MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE);
  MatSetOption(A, MAT_SPD, PETSC_TRUE);

  // The rigid-body modes, orthonormalised, as GAMG's near-null space.
  const Eigen::MatrixXd& modes = settings.near_null_space;
  if (modes.cols() > 0 && modes.rows() == n) {
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(modes);
    const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(n, modes.cols());
    std::vector<Vec> vectors(modes.cols());
    for (Eigen::Index k = 0; k < modes.cols(); ++k) {
      MatCreateVecs(A, &vectors[k], nullptr);
      PetscScalar* local = nullptr;
      VecGetArray(vectors[k], &local);
      order.to_local(Q.col(k), first_row, end_row, local);
      VecRestoreArray(vectors[k], &local);
    }
    MatNullSpace space = nullptr;
    code = MatNullSpaceCreate(PETSC_COMM_WORLD, PETSC_FALSE, static_cast<PetscInt>(vectors.size()), vectors.data(),
                              &space);
    if (!code) code = MatSetNearNullSpace(A, space);
    MatNullSpaceDestroy(&space);
    for (Vec& v : vectors) VecDestroy(&v);
    if (code) return fail("MatSetNearNullSpace", code);
  }

  // Quadratic elements: the P1 level (P2 → P1 interpolation and its rigid-body modes).
  MultigridData data;
  data.A = A;
  const CoarseSpace& space = settings.coarse_space;
  if (!space.empty() && space.interpolation.rows() == n) {
    CoarseLevelInput input;
    input.interpolation = &space.interpolation;
    input.modes = &space.near_null_space;
    input.column_vertex = &space.column_vertex;
    input.vertex_row = &space.column_dof;
    input.block_size = space.block_size;
    if ((code = coarse.create(input, order, first_row, end_row, A))) return fail("the P1 level", code);
    data.coarse_interpolation = coarse.interpolation();
    data.coarse_modes = coarse.modes();
  }

  // CG + the multigrid of multigrid.hpp by default; the options database may change any of it.
  if ((code = KSPCreate(PETSC_COMM_WORLD, &ksp))) return fail("KSPCreate", code);
  KSPSetOperators(ksp, A, A);
  KSPSetType(ksp, KSPCG);
  PC pc = nullptr;
  KSPGetPC(ksp, &pc);
  KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED);                        // the rule bounds the true residual
  KSPSetTolerances(ksp, 0.0, 0.0, PETSC_DEFAULT, kMaxKrylovIterations);  // only the inner rule stops
  KSPConvergedDefaultCreate(&default_test);
  KSPSetConvergenceTest(ksp, converged, this, nullptr);
  // hypre 2.26's BoomerAMG with interpolation vectors ends this process with a segmentation
  // fault on this K (in hypre_BoomerAMG_LNExpandInterp, scenes/hertz-sphere.json), where the
  // petsc backend's A takes them: refused as bad input before hypre sees them.
  PetscBool vector_interpolation = PETSC_FALSE;
  PetscOptionsHasName(nullptr, nullptr, "-pc_hypre_boomeramg_vec_interp_variant", &vector_interpolation);
  if (vector_interpolation) {
    options_error = true;
    message =
        "-pc_hypre_boomeramg_vec_interp_variant: hypre 2.26 crashes with it on the PETSc solver of K "
        "(--linear-solver petsc); the petsc backend (--backend petsc) takes it";
    return false;
  }
  Stopwatch clock;
  MultigridStatistics multigrid;
  // Linear elements: PETSc's GAMG as before (its defaults; the tuned settings measured no
  // better on these sizes, and LBFGS's inner solves in nlopt are sensitive to the change).
  if (!data.coarse_interpolation) {
    PCSetType(pc, PCGAMG);
  } else if ((code = set_up_multigrid(pc, data, &coarse_operator, &multigrid))) {
    return bad_options("the preconditioner's set-up", code);
  }
  if ((code = KSPSetFromOptions(ksp))) return bad_options("KSPSetFromOptions", code);
  // A Krylov method other than CG measures its unpreconditioned residual only with the
  // preconditioner on the right: take that side unless the user chose a norm or side.
  KSPType type = nullptr;
  KSPGetType(ksp, &type);
  PetscBool norm_given = PETSC_FALSE, side_given = PETSC_FALSE, is_cg = PETSC_FALSE;
  PetscOptionsHasName(nullptr, nullptr, "-ksp_norm_type", &norm_given);
  PetscOptionsHasName(nullptr, nullptr, "-ksp_pc_side", &side_given);
  PetscStrcmp(type, KSPCG, &is_cg);
  if (!is_cg && !norm_given && !side_given) KSPSetPCSide(ksp, PC_RIGHT);

  code = KSPSetUp(ksp);
  if (code == PETSC_ERR_SUP && !norm_given && !side_given) {
    // Some methods (MINRES, ...) measure only the preconditioned residual: take PETSc's own
    // norm and side for them. The inner rule then bounds that norm, not the true residual;
    // the certificate still measures the true one.
    KSPSetNormType(ksp, KSP_NORM_DEFAULT);
    KSPSetPCSide(ksp, PC_SIDE_DEFAULT);
    code = KSPSetUp(ksp);
    preconditioned_norm = true;
  }
  if (code) return fail("KSPSetUp", code);
  setup_seconds += clock.seconds();
  PCType pc_type = nullptr;
  KSPGetPC(ksp, &pc);
  PCGetType(pc, &pc_type);
  KSPGetType(ksp, &type);
  std::ostringstream levels;
  levels.precision(3);
  if (multigrid.levels > 0)
    levels << " (" << multigrid.levels << " levels, grid complexity " << multigrid.grid_complexity
           << ", operator complexity " << multigrid.operator_complexity << ")";
  method = std::string(type ? type : "?") + " + " +
           (multigrid.method.empty() ? (pc_type ? pc_type : "?") : multigrid.method) + levels.str() +
           (modes.cols() > 0 ? ", " + std::to_string(modes.cols()) + " near-null modes" : "") +
           (preconditioned_norm ? ", preconditioned residual norm" : "");

  MatCreateVecs(A, &x, &b);
  if ((code = VecScatterCreateToAll(x, &to_all, &x_all))) return fail("VecScatterCreateToAll", code);
  ok = true;
  return true;
}

bool PetscSolver::ok() const {
  std::lock_guard<std::mutex> lock(petsc_mutex());
  return impl_->ok;
}
const std::string& PetscSolver::message() const { return impl_->message; }
int PetscSolver::size() const { return impl_->n; }

std::vector<std::string> PetscSolver::warnings() const {
  std::lock_guard<std::mutex> lock(petsc_mutex());
  return impl_->warnings;
}

LinearSolverStatistics PetscSolver::statistics() const {
  std::lock_guard<std::mutex> lock(petsc_mutex());
  LinearSolverStatistics s;
  s.name = "petsc";
  s.method = impl_->method;
  s.setup_seconds = impl_->setup_seconds;
  s.solves = impl_->solves;
  s.iterations = impl_->iterations;
  return s;
}

Eigen::VectorXd PetscSolver::solve(const Eigen::VectorXd& rhs, const Eigen::VectorXd& guess) const {
  Impl& m = *impl_;
  std::lock_guard<std::mutex> lock(petsc_mutex());
  const bool warm = guess.size() == m.n && guess.allFinite();
  if (!m.ok || rhs.size() != m.n) return warm ? guess : Eigen::VectorXd::Zero(rhs.size());
  // The solver stands for scale·A: A y = b, x = y / scale, so y starts from scale·guess.
  const double bound = rhs.cwiseAbs().maxCoeff();
  if (bound == 0) return Eigen::VectorXd::Zero(m.n);
  PetscRuntime::instance(m.options).use_options(m.options);
  PetscScalar* local = nullptr;
  VecGetArray(m.b, &local);
  m.order.to_local(rhs, m.first_row, m.end_row, local);
  VecRestoreArray(m.b, &local);
  VecGetArray(m.x, &local);
  m.order.to_local(warm ? Eigen::VectorXd(scale_ * guess) : Eigen::VectorXd::Zero(m.n), m.first_row, m.end_row, local);
  VecRestoreArray(m.x, &local);
  KSPSetInitialGuessNonzero(m.ksp, warm ? PETSC_TRUE : PETSC_FALSE);
  m.target = kInnerFraction * m.tol * bound;

  PetscErrorCode code = KSPSolve(m.ksp, m.b, m.x);
  PetscInt iterations = 0;
  KSPGetIterationNumber(m.ksp, &iterations);
  ++m.solves;
  m.iterations += iterations;
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  if (!code) code = KSPGetConvergedReason(m.ksp, &reason);
  if (code) {
    m.fail("KSPSolve", code);
  } else if (reason < 0) {
    m.ok = false;
    m.message = reason_text(m.ksp, iterations, m.target);
  }
  if (!m.checked_unused && PetscRuntime::instance(m.options).generation() == m.generation) {
    m.checked_unused = true;
    for (const std::string& option : PetscRuntime::instance(m.options).unused(m.options))
      m.warnings.push_back("PETSc option " + option + " was not used (PETSc's -options_left)");
  }

  // Every rank receives the whole solution (the backends iterate on full vectors).
  Eigen::VectorXd out = gather_whole(m.to_all, m.x, m.x_all, m.order, m.n) / scale_;
  if (!out.allFinite()) {
    if (m.ok) {
      m.ok = false;
      m.message = "the PETSc KSP returned a solution that is not finite";
    }
    out = warm ? guess : Eigen::VectorXd::Zero(m.n);
  }
  return out;
}

}  // namespace

std::shared_ptr<const LinearSolver> make_petsc_solver(const Eigen::SparseMatrix<double>& K,
                                                      const LinearSolverOptions& options, const MatrixLayout& layout) {
  auto impl = std::make_shared<PetscSolver::Impl>();
  const std::string petsc_options = petsc_options_of(options.library_options);
  {
    std::lock_guard<std::mutex> lock(petsc_mutex());
    PetscRuntime& runtime = PetscRuntime::instance(petsc_options);
    runtime.use_options(petsc_options);
    impl->generation = runtime.generation();
    impl->n = static_cast<int>(K.rows());
    impl->tol = options.tol;
    impl->options = petsc_options;
    Stopwatch clock;
    if (K.rows() != K.cols()) {
      impl->message = "matrix is not square";
    } else {
      Eigen::SparseMatrix<double> compressed = K;
      compressed.makeCompressed();
      impl->set_up(compressed, options, layout);
    }
    impl->setup_seconds = clock.seconds();
  }
  // Thrown without the lock: unwinding destroys impl, whose destructor takes it.
  if (impl->options_error) throw InputError("petsc_options", "= \"" + petsc_options + "\": " + impl->message);
  return std::make_shared<PetscSolver>(impl, 1.0);
}

}  // namespace contactqp::detail
