// solve_distributed_pdas() (distributed_pdas.hpp): petsc_bound_qp.cpp's pdas loop, each rank
// with its own rows and bounds.
#include "distributed_pdas.hpp"

#include <mpi.h>
#include <petscksp.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <set>
#include <sstream>

#include "contactqp/errors.hpp"
#include "contactqp/timer.hpp"
#include "petsc/petsc_runtime.hpp"

namespace contactqp::detail {
namespace {

// The inner rule of petsc_solver.cpp (docs/linear-solvers.md) and the loop's constants, as in
// petsc_bound_qp.cpp: ‖r‖₂ ≤ 1e-3 · tol · F; loose steps at 1e-2 of the last KKT residual; a
// kept preconditioner set up afresh after a solve of more than 200 CG iterations.
constexpr double kInnerFraction = 1e-3;
constexpr double kLooseFraction = 1e-2;
constexpr PetscInt kRebuildIterations = 200;
constexpr double kRoundOff = 100 * 2.220446049250313e-16;
constexpr PetscInt kMaxKrylovIterations = 10000;

struct PetscFailure {
  std::string message;
};

void check(PetscErrorCode code, const char* what) {
  if (code) throw PetscFailure{std::string(what) + ": " + error_text(code)};
}

double max_over_ranks(double x) {
  MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  return x;
}

// A fingerprint of the whole active set, the same whatever the ranks: the sum of a mixed hash
// of each active bound's global row (the loop remembers the sets it has seen by it).
std::uint64_t fingerprint(const std::vector<char>& active, const std::vector<PetscInt>& bounded) {
  std::uint64_t sum = 0;
  for (std::size_t i = 0; i < active.size(); ++i)
    if (active[i]) {
      std::uint64_t h = static_cast<std::uint64_t>(bounded[i]) + 0x9e3779b97f4a7c15ULL;
      h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ULL;
      h = (h ^ (h >> 27)) * 0x94d049bb133111ebULL;
      sum += h ^ (h >> 31);
    }
  MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_UINT64_T, MPI_SUM, PETSC_COMM_WORLD);
  return sum;
}

std::string number_text(double x) {
  std::ostringstream text;
  text.precision(4);
  text << x;
  return text.str();
}

double matrix_bytes(Mat M) {
  MatInfo info;
  PetscInt rows = 0, columns = 0;
  if (MatGetInfo(M, MAT_LOCAL, &info) || MatGetLocalSize(M, &rows, &columns)) return 0;
  return info.nz_allocated * (sizeof(PetscScalar) + sizeof(PetscInt)) + (rows + 1.0) * sizeof(PetscInt);
}

// The loop's PETSc objects; after the loop, the solver of A for the certificate.
class Loop final : public DistributedSolverOfA {
 public:
  Mat A = nullptr;  // the problem's
  Mat W = nullptr;
  KSP ksp = nullptr;
  Vec r = nullptr, rhs = nullptr, good = nullptr;
  MatNullSpace modes = nullptr;
  void* default_test = nullptr;
  double target = 0, A_norm = 0, tol = 1e-8;
  bool options_error = false;
  std::string options;

  ~Loop() override {
    if (petsc_finalized()) return;
    for (Vec* v : {&r, &rhs, &good})
      if (*v) VecDestroy(v);
    if (modes) MatNullSpaceDestroy(&modes);
    if (ksp) KSPDestroy(&ksp);
    if (W) MatDestroy(&W);
    if (default_test) KSPConvergedDefaultDestroy(default_test);
  }

  static PetscErrorCode converged(KSP ksp, PetscInt it, PetscReal rnorm, KSPConvergedReason* reason, void* context) {
    Loop& loop = *static_cast<Loop*>(context);
    PetscCall(KSPConvergedDefault(ksp, it, rnorm, reason, loop.default_test));
    if (*reason != KSP_CONVERGED_ITERATING) return 0;
    double target = loop.target;
    if (rnorm > target && rnorm <= 1e6 * target) {
      Vec x = nullptr;
      PetscReal x_norm = 0;
      PetscCall(KSPBuildSolution(ksp, nullptr, &x));
      PetscCall(VecNorm(x, NORM_INFINITY, &x_norm));
      target = std::max(target, kRoundOff * loop.A_norm * x_norm);
    }
    if (rnorm <= target) *reason = KSP_CONVERGED_ATOL;
    return 0;
  }

  bool solve(Vec b, Vec x, double force) override {
    std::lock_guard<std::mutex> lock(petsc_mutex());
    PetscRuntime::instance(options).use_options(options);
    if (KSPSetOperators(ksp, A, W) || KSPSetReusePreconditioner(ksp, PETSC_TRUE)) return false;
    target = kInnerFraction * tol * force;
    KSPSetInitialGuessNonzero(ksp, PETSC_FALSE);
    if (KSPSolve(ksp, b, x)) return false;
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    KSPGetConvergedReason(ksp, &reason);
    return reason > 0;
  }

  double bytes() const {
    double total = matrix_bytes(A) + (W ? matrix_bytes(W) : 0.0);
    PC pc = nullptr;
    KSPGetPC(ksp, &pc);
    PetscBool multigrid = PETSC_FALSE;
    PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(pc), &multigrid, PCGAMG, PCMG, "");
    PetscInt levels = 0;
    if (!multigrid || PCMGGetLevels(pc, &levels)) return total;
    for (PetscInt level = 0; level < levels; ++level) {
      KSP smoother = nullptr;
      Mat op = nullptr;
      if (level + 1 < levels && !PCMGGetSmoother(pc, level, &smoother) && !KSPGetOperators(smoother, &op, nullptr) &&
          op)
        total += matrix_bytes(op);
      Mat interpolation = nullptr;
      if (level > 0 && !PCMGGetInterpolation(pc, level, &interpolation) && interpolation)
        total += matrix_bytes(interpolation);
    }
    return total;
  }
};

void set_up(Loop& loop, const DistributedBoundQp& qp) {
  loop.A = qp.A;
  MatNorm(qp.A, NORM_INFINITY, &loop.A_norm);
  if (!qp.near_null_space.empty()) {
    check(MatNullSpaceCreate(PETSC_COMM_WORLD, PETSC_FALSE, static_cast<PetscInt>(qp.near_null_space.size()),
                             qp.near_null_space.data(), &loop.modes),
          "MatNullSpaceCreate");
    check(MatSetNearNullSpace(qp.A, loop.modes), "MatSetNearNullSpace");
  }
  check(MatDuplicate(qp.A, MAT_COPY_VALUES, &loop.W), "MatDuplicate");
  check(KSPCreate(PETSC_COMM_WORLD, &loop.ksp), "KSPCreate");
  KSPSetType(loop.ksp, KSPCG);
  PC pc = nullptr;
  KSPGetPC(loop.ksp, &pc);
  PCSetType(pc, PCGAMG);
  // As petsc_bound_qp.cpp: GAMG set up afresh for each active set (docs/petsc.md).
  PCGAMGSetReuseInterpolation(pc, PETSC_FALSE);
  KSPSetNormType(loop.ksp, KSP_NORM_UNPRECONDITIONED);
  KSPSetTolerances(loop.ksp, 0.0, 0.0, PETSC_DEFAULT, kMaxKrylovIterations);
  KSPConvergedDefaultCreate(&loop.default_test);
  KSPSetConvergenceTest(loop.ksp, Loop::converged, &loop, nullptr);
  KSPSetOperators(loop.ksp, loop.W, loop.W);
  if (PetscErrorCode code = KSPSetFromOptions(loop.ksp)) {
    loop.options_error = true;
    check(code, "KSPSetFromOptions");
  }
  KSPSetInitialGuessNonzero(loop.ksp, PETSC_TRUE);
  check(MatCreateVecs(qp.A, &loop.r, &loop.rhs), "MatCreateVecs");
  check(VecDuplicate(loop.r, &loop.good), "VecDuplicate");
  check(VecSet(loop.good, 0.0), "VecSet");
}

std::string reason_text(KSP ksp, PetscInt iterations, double target) {
  const char* name = nullptr;
  KSPGetConvergedReasonString(ksp, &name);
  PetscReal residual = 0;
  KSPGetResidualNorm(ksp, &residual);
  std::ostringstream text;
  text.precision(3);
  text << "the PETSc KSP did not converge: KSP_" << (name ? name : "unknown reason") << " after " << iterations
       << " iterations at residual " << residual << " (target " << target << ")";
  return text.str();
}

void iterate(Loop& loop, const DistributedBoundQp& qp, const DistributedPdasOptions& options,
             DistributedPdasResult& result) {
  const int m = static_cast<int>(qp.bounded.size());
  PetscInt first = 0, end = 0;
  MatGetOwnershipRange(qp.A, &first, &end);
  Vec x = nullptr;
  check(VecDuplicate(loop.r, &x), "VecDuplicate");
  result.v = x;
  // c_i = A_ii: the semismooth Newton step's weight.
  check(MatGetDiagonal(qp.A, loop.r), "MatGetDiagonal");
  std::vector<double> c(m);
  {
    const PetscScalar* d = nullptr;
    VecGetArrayRead(loop.r, &d);
    for (int i = 0; i < m; ++i) c[i] = d[qp.bounded[i] - first];
    VecRestoreArrayRead(loop.r, &d);
  }
  PetscReal b_norm = 0;
  VecNorm(qp.b, NORM_INFINITY, &b_norm);
  // The diagonal of a fixed row: the mean of A's diagonal at the bounds (petsc_bound_qp.cpp).
  double sums[2] = {0, static_cast<double>(m)};
  for (int i = 0; i < m; ++i) sums[0] += c[i];
  MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  double fixed_diagonal = sums[1] > 0 ? sums[0] / sums[1] : 1;
  if (!(fixed_diagonal > 0)) fixed_diagonal = 1;

  std::vector<double> mu(m, 0.0);
  std::vector<char> active(m, 0);
  std::set<std::uint64_t> seen;
  bool tight = false, rebuild = false;
  double previous_residual = 1.0;
  std::vector<PetscInt> rows;
  for (int k = 1;; ++k) {
    seen.insert(fingerprint(active, qp.bounded));
    check(MatCopy(qp.A, loop.W, SAME_NONZERO_PATTERN), "MatCopy");
    check(VecCopy(loop.good, x), "VecCopy");
    rows.clear();
    PetscScalar* values = nullptr;
    VecGetArray(x, &values);
    for (int i = 0; i < m; ++i)
      if (active[i]) {
        values[qp.bounded[i] - first] = qp.upper[i];
        rows.push_back(qp.bounded[i]);
      }
    VecRestoreArray(x, &values);
    check(VecCopy(qp.b, loop.rhs), "VecCopy");
    check(MatZeroRowsColumns(loop.W, static_cast<PetscInt>(rows.size()), rows.data(), fixed_diagonal, x, loop.rhs),
          "MatZeroRowsColumns");
    if (loop.modes) check(MatSetNearNullSpace(loop.W, loop.modes), "MatSetNearNullSpace");
    check(KSPSetOperators(loop.ksp, loop.W, loop.W), "KSPSetOperators");
    const bool keep = options.reuse_preconditioner && result.preconditioner_setups > 0 && !rebuild;
    check(KSPSetReusePreconditioner(loop.ksp, keep ? PETSC_TRUE : PETSC_FALSE), "KSPSetReusePreconditioner");
    if (!keep) {
      ++result.preconditioner_setups;
      check(KSPSetUp(loop.ksp), "KSPSetUp");
    }
    double mu_max = 0;
    for (double value : mu) mu_max = std::max(mu_max, std::abs(value));
    const double force = std::max<double>(b_norm, max_over_ranks(mu_max));
    const double final_target = force > 0 ? kInnerFraction * options.tol * force : kInnerFraction * options.tol;
    const bool solved_tight = tight || !options.inexact;
    loop.target = solved_tight ? final_target : std::max(final_target, kLooseFraction * previous_residual * force);
    KSPSetInitialGuessNonzero(loop.ksp, PETSC_TRUE);
    check(KSPSolve(loop.ksp, loop.rhs, x), "KSPSolve");
    result.petsc_bytes = std::max(result.petsc_bytes, loop.bytes());
    PetscInt iterations = 0;
    KSPGetIterationNumber(loop.ksp, &iterations);
    result.krylov_iterations += iterations;
    ++result.linear_solves;
    result.iterations = k;
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    KSPGetConvergedReason(loop.ksp, &reason);
    int mine = keep && (reason < 0 || iterations > kRebuildIterations), any = 0;
    MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
    rebuild = any != 0;
    if (reason < 0 && keep && k < options.max_iterations) continue;  // the same step, set up afresh
    if (reason < 0) {
      result.status = Status::NumericalError;
      result.message = reason_text(loop.ksp, iterations, loop.target);
      break;
    }
    check(VecCopy(x, loop.good), "VecCopy");
    // μ = b − A v on the active bounds, 0 on the others.
    check(MatMult(qp.A, x, loop.r), "MatMult");
    const PetscScalar *Av = nullptr, *b = nullptr, *v = nullptr;
    VecGetArrayRead(loop.r, &Av);
    VecGetArrayRead(qp.b, &b);
    VecGetArrayRead(x, &v);
    int finite = 1;
    for (int i = 0; i < m; ++i) mu[i] = active[i] ? b[qp.bounded[i] - first] - Av[qp.bounded[i] - first] : 0.0;
    for (PetscInt row = 0; row < end - first; ++row) finite = finite && std::isfinite(v[row]);
    for (double value : mu) finite = finite && std::isfinite(value);
    std::vector<char> next(m, 0);
    for (int i = 0; i < m; ++i) next[i] = mu[i] + c[i] * (v[qp.bounded[i] - first] - qp.upper[i]) > 0;
    VecRestoreArrayRead(loop.r, &Av);
    VecRestoreArrayRead(qp.b, &b);
    VecRestoreArrayRead(x, &v);
    MPI_Allreduce(MPI_IN_PLACE, &finite, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
    if (!finite) {
      result.status = Status::NumericalError;
      result.message = "the PETSc KSP returned a solution that is not finite";
      break;
    }
    result.residual = options.residual(x, mu);
    previous_residual = std::min(1.0, result.residual);
    int same = next == active;
    MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
    const bool repeats = seen.count(fingerprint(next, qp.bounded)) > 0;
    if (!solved_tight && (result.residual <= options.tol || same || repeats)) {
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
    if (same) {
      result.status = Status::NumericalError;
      result.message = "the active set settled with residual " + number_text(result.residual) +
                       " above tol: the inner KSP solves are not accurate enough (a smaller -ksp_rtol may help)";
      break;
    }
    if (repeats) {
      result.status = Status::NumericalError;
      result.message = "the active-set steps cycled at residual " + number_text(result.residual);
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
  check(VecCopy(loop.good, x), "VecCopy");
  result.mu.resize(m);
  for (int i = 0; i < m; ++i) result.mu[i] = std::max(0.0, mu[i]);
  long long n_active = std::count(active.begin(), active.end(), 1);
  MPI_Allreduce(MPI_IN_PLACE, &n_active, 1, MPI_LONG_LONG, MPI_SUM, PETSC_COMM_WORLD);
  result.active = n_active;
  KSPType type = nullptr;
  PCType pc_type = nullptr;
  PC pc = nullptr;
  KSPGetType(loop.ksp, &type);
  KSPGetPC(loop.ksp, &pc);
  PCGetType(pc, &pc_type);
  result.method = std::string("pdas, ") + (type ? type : "?") + " + " + (pc_type ? pc_type : "?") +
                  (loop.modes ? ", " + std::to_string(qp.near_null_space.size()) + " near-null modes" : "") +
                  ", distributed";
}

}  // namespace

DistributedPdasResult::DistributedPdasResult(DistributedPdasResult&& other) noexcept { *this = std::move(other); }

DistributedPdasResult& DistributedPdasResult::operator=(DistributedPdasResult&& other) noexcept {
  std::swap(status, other.status);
  std::swap(message, other.message);
  std::swap(v, other.v);
  std::swap(mu, other.mu);
  std::swap(iterations, other.iterations);
  std::swap(krylov_iterations, other.krylov_iterations);
  std::swap(linear_solves, other.linear_solves);
  std::swap(preconditioner_setups, other.preconditioner_setups);
  std::swap(active, other.active);
  std::swap(residual, other.residual);
  std::swap(setup_seconds, other.setup_seconds);
  std::swap(iterate_seconds, other.iterate_seconds);
  std::swap(method, other.method);
  std::swap(matrix_bytes, other.matrix_bytes);
  std::swap(petsc_bytes, other.petsc_bytes);
  std::swap(warnings, other.warnings);
  std::swap(solver_of_A, other.solver_of_A);
  return *this;
}

DistributedPdasResult::~DistributedPdasResult() {
  if (v && !petsc_finalized()) VecDestroy(&v);
}

DistributedPdasResult solve_distributed_pdas(const DistributedBoundQp& qp, const DistributedPdasOptions& options) {
  DistributedPdasResult result;
  auto loop = std::make_shared<Loop>();
  loop->tol = options.tol;
  loop->options = options.petsc_options;
  bool options_error = false;
  {
    std::lock_guard<std::mutex> lock(petsc_mutex());
    PetscRuntime& runtime = PetscRuntime::instance(options.petsc_options);
    runtime.use_options(options.petsc_options);
    const long generation = runtime.generation();
    std::string failure;
    Stopwatch clock;
    int rank = 0;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    try {
      set_up(*loop, qp);
    } catch (const PetscFailure& error) {
      failure = error.message;
    }
    result.setup_seconds = clock.seconds();
    // The ranks agree on the set-up's outcome before the loop's first collective call.
    int failing = failure.empty() ? INT_MAX : rank, first_failing = INT_MAX;
    MPI_Allreduce(&failing, &first_failing, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
    if (first_failing == INT_MAX) {
      clock.restart();
      try {
        iterate(*loop, qp, options, result);
      } catch (const PetscFailure& error) {
        failure = error.message;
      }
      result.iterate_seconds = clock.seconds();
    } else if (failure.empty()) {
      failure = "the PETSc set-up failed on rank " + std::to_string(first_failing);
    }
    options_error = loop->options_error;
    if (!failure.empty()) {
      result.status = Status::NumericalError;
      result.message = failure;
    }
    double mine[2] = {matrix_bytes(qp.A), result.petsc_bytes};
    MPI_Allreduce(MPI_IN_PLACE, mine, 2, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
    result.matrix_bytes = mine[0];
    result.petsc_bytes = mine[1];
    if (runtime.generation() == generation)
      for (const std::string& option : runtime.unused(options.petsc_options))
        result.warnings.push_back("PETSc option " + option + " was not used (PETSc's -options_left)");
  }
  int any_options_error = options_error;
  MPI_Allreduce(MPI_IN_PLACE, &any_options_error, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  if (any_options_error) throw InputError("petsc_options", "= \"" + options.petsc_options + "\": " + result.message);
  result.solver_of_A = loop;
  return result;
}

}  // namespace contactqp::detail
