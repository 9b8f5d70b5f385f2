// solve_bound_pdas() (bound_pdas.hpp): the active-set loop, its P1 start and its solver of A.
#include "bound_pdas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <sstream>

#include "contactqp/timer.hpp"
#include "ksp_helpers.hpp"
#include "masked_system.hpp"
#include "petsc_runtime.hpp"
#include "truncation.hpp"

namespace contactqp::detail {
namespace {

// The inner rule and its round-off floor: kInnerFraction and kRoundOff, ksp_helpers.hpp.
// A loose step's reduction: kLooseReduction, bound_pdas.hpp.
// The P1 start stops at this relative KKT residual or when its active set repeats: the fine
// loop only needs its active set and a good first iterate.
constexpr double kP1Tolerance = 1e-6;
// The weight of the slip against the tangential multiplier in the next state's test,
// z = λ_T + c (v_T − offset) with c = this times A's diagonal there. Any c > 0 has the same
// fixed points; the path differs. Measured on the shipped 2D frictional scenes at tol 1e-10:
// 1 and 10 cycle on sliding-block.json, 0.1 cycles on mindlin-on-plane.json, 0.01 converges on
// all three (mindlin-on-plane, mindlin-cylinders, sliding-block) to active_set's answer. A small
// c trusts the multiplier, which the step's solve computes, over a slip it has just fixed to 0.
constexpr double kTangentialWeight = 0.01;
// 3D: a slipping row's Newton term β (I − n nᵀ) (TangentialStates) joins W while β is at most
// this times A's diagonal there; a stiffer row is pinned instead (β → ∞: it slips along n only).
// The term changes the path, not the answer (at the answer the slip is along n, where it is 0),
// and the preconditioner does not see it (MaskedSystem::smoother_op), so a large β only slows
// CG. Measured on mindlin-spheres.json (125 018 DOFs, tol 1e-10, three load steps): 1 → 138
// steps along the path, 1974 CG iterations, 189 s; 10 → 100, 1868, 185 s; no pins (1e9) →
// 105, 2140, 223 s. On a 14 200-DOF coarsening: 90, 74 and 72 steps.
constexpr double kNewtonBound = 10.0;
// 3D: with the sets settled, the Newton steps on the slip directions go on at the final rule
// while the residual falls; this many steps without halving the best residual is a stall.
constexpr int kStalledSteps = 25;
// The energy solve's delay d: θ − rᵀx_k, the error left in rᵀx_k, is estimated by
// rᵀx_{k+d} − rᵀx_k (Strakoš and Tichý's lower bound on CG's A-norm error, which is sharp
// once the convergence is steady; with a multigrid preconditioner each iteration gains about
// a digit, so four iterations more than cover the tail).
constexpr std::size_t kEnergyDelay = 4;

// When a KSP solve stops: KSPConvergedDefault first (a user's -ksp_rtol, -ksp_max_it,
// divergence), then ‖r‖₂ ≤ target — or, for a loose step, ≤ max(target, reduction · ‖r₀‖₂) —
// with the round-off floor 100 ε ‖A‖∞ ‖x‖∞ below which CG only stagnates.
// An energy solve (KeptSolverOfA::energy) also stops when rhsᵀx has grown by at most
// energy_tolerance over the last kEnergyDelay iterations.
struct StoppingRule {
  double target = 0;
  double reduction = 0;  // > 0: a loose step
  double A_norm = 0;
  double initial = 0;
  void* default_test = nullptr;
  Vec energy_rhs = nullptr;  // set: an energy solve
  double energy_tolerance = 0;
  std::vector<double> energies;  // rhsᵀx_k, k = 0, 1, …

  static PetscErrorCode test(KSP ksp, PetscInt it, PetscReal rnorm, KSPConvergedReason* reason, void* context) {
    PetscFunctionBeginUser;
    StoppingRule& rule = *static_cast<StoppingRule*>(context);
    PetscCall(KSPConvergedDefault(ksp, it, rnorm, reason, rule.default_test));
    if (it == 0) rule.initial = rnorm;
    const double target = rule.reduction > 0 ? std::max(rule.target, rule.reduction * rule.initial) : rule.target;
    PetscCall(inner_stopping_rule(ksp, rnorm, target, rule.A_norm, reason));
    if (rule.energy_rhs && *reason == KSP_CONVERGED_ITERATING) {
      Vec x = nullptr;
      PetscScalar energy = 0;
      PetscCall(KSPBuildSolution(ksp, nullptr, &x));
      PetscCall(VecDot(rule.energy_rhs, x, &energy));
      rule.energies.push_back(energy);
      const std::size_t n = rule.energies.size();
      if (n > kEnergyDelay && rule.energies[n - 1] - rule.energies[n - 1 - kEnergyDelay] <= rule.energy_tolerance)
        *reason = KSP_CONVERGED_ATOL;
    }
    PetscFunctionReturn(0);
  }
};

// A CG solver of a level's masked system, preconditioned by the masked `inner` PC.
struct LevelSolver {
  MaskedSystem mask;
  KSP ksp = nullptr;
  StoppingRule rule;

  ~LevelSolver() {
    if (petsc_finalized()) return;
    if (ksp) KSPDestroy(&ksp);
    if (rule.default_test) KSPConvergedDefaultDestroy(rule.default_test);
  }

  PetscErrorCode create(Mat A, PC inner, const char* prefix) {
    PetscFunctionBeginUser;
    PetscCall(mask.create(A));
    PetscCall(MatNorm(A, NORM_INFINITY, &rule.A_norm));
    PetscCall(KSPCreate(PetscObjectComm(reinterpret_cast<PetscObject>(A)), &ksp));
    PetscCall(KSPSetOptionsPrefix(ksp, prefix));
    PetscCall(KSPSetType(ksp, KSPCG));
    PetscCall(KSPSetOperators(ksp, mask.op(), A));
    PetscCall(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED));
    PetscCall(KSPSetTolerances(ksp, 0.0, 0.0, PETSC_DEFAULT, kMaxKrylovIterations));
    PetscCall(KSPConvergedDefaultCreate(&rule.default_test));
    PetscCall(KSPSetConvergenceTest(ksp, StoppingRule::test, &rule, nullptr));
    PC outer = nullptr;
    PetscCall(KSPGetPC(ksp, &outer));
    PetscCall(mask.wrap(outer, inner));
    // The shell must stay a shell whatever -pc_type the user gave (that one is the inner PC's).
    PetscCall(PCSetOptionsPrefix(outer, "contactqp_masked_"));
    PetscCall(KSPSetFromOptions(ksp));
    PetscCall(KSPSetInitialGuessNonzero(ksp, PETSC_TRUE));
    PetscFunctionReturn(0);
  }

  PetscErrorCode solve(Vec rhs, Vec x, double target, double reduction, PetscInt* iterations,
                       KSPConvergedReason* reason) {
    PetscFunctionBeginUser;
    rule.target = target;
    rule.reduction = reduction;
    PetscCall(KSPSolve(ksp, rhs, x));
    PetscCall(KSPGetIterationNumber(ksp, iterations));
    PetscCall(KSPGetConvergedReason(ksp, reason));
    PetscFunctionReturn(0);
  }
};

// What outlives the loop for the solver of A: the fine level's solver and hierarchy.
struct FineState {
  PC inner = nullptr;  // the hierarchy on A
  Mat P1_operator = nullptr;
  LevelSolver level;
  TruncatedHierarchy truncation;
  long long iterations = 0;
  double tol = 1e-8;

  ~FineState() {
    if (petsc_finalized()) return;
    if (inner) PCDestroy(&inner);
    if (P1_operator) MatDestroy(&P1_operator);
  }
};

class KeptSolverOfA final : public SolverOfA {
 public:
  explicit KeptSolverOfA(std::shared_ptr<FineState> state) : state_(std::move(state)) {}
  bool solve(Vec rhs, Vec x, double force) override {  // the caller holds petsc_mutex()
    FineState& s = *state_;
    // No row fixed and no Newton term: W is A, and the coarse operators are A's again.
    s.level.mask.fix({});
    s.level.mask.couple({});
    s.level.mask.pin({});
    if (s.truncation.fix_rows({})) return false;
    if (VecSet(x, 0.0)) return false;
    const double target = kInnerFraction * s.tol * std::max(force, 1e-300);
    PetscInt iterations = 0;
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    if (s.level.solve(rhs, x, target, 0.0, &iterations, &reason)) return false;
    s.iterations += iterations;
    return reason > 0;
  }
  bool energy(Vec rhs, Vec x, double force, double tolerance, double* theta) override {
    FineState& s = *state_;
    s.level.rule.energy_rhs = rhs;
    s.level.rule.energy_tolerance = tolerance;
    s.level.rule.energies.clear();
    const bool solved = solve(rhs, x, force);
    s.level.rule.energy_rhs = nullptr;
    if (!solved || VecDot(rhs, x, theta)) return false;
    return true;
  }
  long long iterations() const override { return state_->iterations; }
  const std::shared_ptr<FineState>& state() const { return state_; }

 private:
  std::shared_ptr<FineState> state_;
};

long long count_over_ranks(long long n, MPI_Comm comm) {
  MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPI_LONG_LONG, MPI_SUM, comm);
  return n;
}

// One level's contact problem for the loop.
struct LevelProblem {
  Mat A = nullptr;
  Vec b = nullptr;
  std::vector<PetscInt> bounded;  // global rows, this rank's, increasing
  std::vector<double> upper;
  // Tresca friction (PetscBoundQp's fields), or n_directions 0.
  int n_directions = 0;
  std::vector<PetscInt> tangential;
  std::vector<double> offset, radius;
};

// The state of a contact row's tangential variables in the loop (Hüeber, Stadler & Wohlmuth's
// semismooth Newton method for Tresca's law, on the primal variables): sticking, they are fixed
// at the offset (no slip) and λ_T = b − A v there; slipping, they are free and λ_T = r n is a
// given force along the direction n. The next state, from z = λ_T + c (v_T − offset) with c
// kTangentialWeight times A's diagonal (one c per row, averaged over its directions): stick
// where ‖z‖ ≤ r, else slip along n = z/‖z‖. In 2D (one direction) that is the primal-dual
// active-set method for the interval [−r, r]. In 3D the direction of a disc must follow the
// steps too. Kept fixed per step and updated between steps, it converged linearly and slowly
// (879 steps on a coarse mindlin-spheres.json, stalling at 1.1e-10); so a slipping row's force
// is linearised in its slip w = v_T − offset, as Newton's method does:
//     λ_T = r n + β P w,   P = I − n nᵀ,   β = c r / (‖z‖ − r)
// (at the answer z = (r + c‖w‖) n, so β = r/‖w‖ and β P is the derivative of r w/‖w‖). The
// term β P joins W (MaskedSystem::couple), symmetric and positive semidefinite, and β P offset
// joins b — while β ≤ kNewtonBound times A's diagonal. A stiffer row (little slip for its
// force: near sticking) is pinned (MaskedSystem::pin): it slips along n only, its force across
// n is measured as λ_T = b − A v, and its direction turns by that force (the limit β → ∞).
struct TangentialStates {
  std::vector<char> stick;        // per contact row
  std::vector<double> direction;  // per tangential variable: n where slipping
  std::vector<double> beta;       // per contact row, 3D: the Newton term's β where slipping (0: none)
  std::vector<double> lambda_t;   // per tangential variable
};

// A 64-bit hash of one integer (splitmix64's finaliser).
std::uint64_t mixed(std::uint64_t h) {
  h += 0x9e3779b97f4a7c15ULL;
  h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ULL;
  h = (h ^ (h >> 27)) * 0x94d049bb133111ebULL;
  return h ^ (h >> 31);
}

// Σ over the active bounds of a mixed hash of their global rows: the same whatever the ranks,
// so that every rank remembers the same sets. With friction each contact row's tangential state
// joins it: stick, or slip (in 2D with its sign), keyed by its first tangential variable.
std::uint64_t fingerprint(const std::vector<char>& active, const std::vector<PetscInt>& bounded, MPI_Comm comm,
                          const LevelProblem* friction = nullptr, const TangentialStates* states = nullptr) {
  std::uint64_t sum = 0;
  for (std::size_t i = 0; i < active.size(); ++i)
    if (active[i]) sum += mixed(static_cast<std::uint64_t>(bounded[i]));
  if (friction && states)
    for (std::size_t j = 0; j < states->stick.size(); ++j) {
      std::size_t t = j * friction->n_directions;
      // Keyed by its first direction with a variable.
      while (t + 1 < (j + 1) * friction->n_directions && friction->tangential[t] < 0) ++t;
      const std::uint64_t code = states->stick[j]             ? 1
                                 : friction->n_directions > 1 ? 2
                                 : states->direction[t] > 0   ? 3
                                                              : 4;
      sum += mixed((static_cast<std::uint64_t>(friction->tangential[t]) << 3) + code + (1ULL << 62));
    }
  MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_UINT64_T, MPI_SUM, comm);
  return sum;
}

struct LoopSettings {
  double tol = 1e-8;
  int max_iterations = 10000;
  bool inexact = true;
  double loose_reduction = kLooseReduction;
  bool final_steps = true;  // false (the P1 start): stop at tol or a repeated set, no final-rule step
  std::function<double(Vec v, const std::vector<double>& mu)> residual;
  std::function<double(Vec v, const std::vector<double>& mu, const std::vector<double>& lambda_t)> friction_residual;
};

struct LoopOutcome {
  Status status = Status::NumericalError;
  std::string message;
  int steps = 0;
  long long krylov_iterations = 0;
  double residual = 0;
};

// The primal-dual active-set loop on one level, from x and `active` (and with friction the
// tangential `states`); μ (and λ_T in `states`) out.
PetscErrorCode active_set_loop(const LevelProblem& level, LevelSolver& solver, TruncatedHierarchy* truncation,
                               const LoopSettings& settings, Vec x, std::vector<char>& active, std::vector<double>& mu,
                               LoopOutcome* outcome, TangentialStates* states = nullptr) {
  PetscFunctionBeginUser;
  const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(level.A));
  PetscInt first = 0;
  PetscCall(MatGetOwnershipRange(level.A, &first, nullptr));
  const std::size_t m = level.bounded.size();
  const int nd = states ? level.n_directions : 0;
  const std::size_t n_tangential = nd ? level.tangential.size() : 0, n_rows = nd ? n_tangential / nd : 0;
  std::vector<double> diagonal(m), tangential_diagonal(n_tangential);
  {
    const PetscScalar* d = nullptr;
    PetscCall(VecGetArrayRead(solver.mask.diagonal(), &d));
    for (std::size_t i = 0; i < m; ++i) diagonal[i] = d[level.bounded[i] - first];
    for (std::size_t t = 0; t < n_tangential; ++t)
      if (level.tangential[t] >= 0) tangential_diagonal[t] = d[level.tangential[t] - first];
    PetscCall(VecRestoreArrayRead(solver.mask.diagonal(), &d));
  }
  PetscReal b_norm = 0;
  PetscCall(VecNorm(level.b, NORM_INFINITY, &b_norm));
  Vec rhs = nullptr, Ax = nullptr, b_step = nullptr;
  PetscCall(VecDuplicate(level.b, &rhs));
  PetscCall(VecDuplicate(level.b, &Ax));
  if (nd) PetscCall(VecDuplicate(level.b, &b_step));
  mu.assign(m, 0.0);
  std::set<std::uint64_t> seen;
  bool tight = !settings.inexact;
  const LevelProblem* friction = nd ? &level : nullptr;
  std::vector<char> pinned(n_rows, 0);  // 3D: slipping rows whose slip across n is kept this step
  double best_tight = std::numeric_limits<double>::infinity();  // 3D: the stall test's
  int stalled_steps = 0;
  for (int k = 1;; ++k) {
    seen.insert(fingerprint(active, level.bounded, comm, friction, states));
    std::vector<std::pair<PetscInt, double>> fixed_values;
    for (std::size_t i = 0; i < m; ++i)
      if (active[i]) fixed_values.emplace_back(level.bounded[i] - first, level.upper[i]);
    for (std::size_t j = 0; j < n_rows; ++j)
      if (states->stick[j])
        for (int d = 0; d < nd; ++d)
          if (level.tangential[j * nd + d] >= 0)
            fixed_values.emplace_back(level.tangential[j * nd + d] - first, level.offset[j * nd + d]);
    std::sort(fixed_values.begin(), fixed_values.end());
    std::vector<PetscInt> fixed;
    std::vector<double> values;
    for (const auto& [row, value] : fixed_values) {
      fixed.push_back(row);
      values.push_back(value);
    }
    if (truncation) PetscCall(truncation->fix_rows(fixed));
    solver.mask.fix(fixed);
    // The slipping rows' friction force, −r n, joins b; in 3D its Newton term −β P (v_T −
    // offset) too, as β P in W and β P offset in b.
    Vec b = level.b;
    if (nd) {
      PetscCall(VecCopy(level.b, b_step));
      PetscScalar* bs = nullptr;
      PetscCall(VecGetArray(b_step, &bs));
      std::vector<MaskedSystem::Block> blocks;
      std::vector<MaskedSystem::Pin> pins;
      const PetscScalar* xs = nullptr;
      PetscCall(VecGetArrayRead(x, &xs));
      for (std::size_t j = 0; j < n_rows; ++j) {
        pinned[j] = 0;
        if (states->stick[j]) continue;
        for (int d = 0; d < nd; ++d)
          if (level.tangential[j * nd + d] >= 0)
            bs[level.tangential[j * nd + d] - first] -= level.radius[j] * states->direction[j * nd + d];
        if (nd == 2 && states->beta[j] > 0) {
          const std::size_t t = j * nd;
          const double n0 = states->direction[t], n1 = states->direction[t + 1];
          const PetscInt r0 = level.tangential[t], r1 = level.tangential[t + 1];
          const double scale = r0 >= 0 && r1 >= 0 ? 0.5 * (tangential_diagonal[t] + tangential_diagonal[t + 1])
                               : r0 >= 0          ? tangential_diagonal[t]
                                                  : tangential_diagonal[t + 1];
          if (r0 >= 0 && r1 >= 0 && states->beta[j] > kNewtonBound * scale) {
            // Stiff (near sticking): β → ∞, the row slips along n only (m·w = 0); so large a
            // term would slow CG, whose preconditioner is built on A alone.
            const double m0 = -n1, m1 = n0;
            pins.push_back({r0 - first, r1 - first, m0, m1, m0 * level.offset[t] + m1 * level.offset[t + 1]});
            pinned[j] = 1;
            continue;
          }
          const double beta = states->beta[j];
          const double p00 = beta * (1 - n0 * n0), p01 = -beta * n0 * n1, p11 = beta * (1 - n1 * n1);
          if (r0 >= 0) bs[r0 - first] += p00 * level.offset[t] + p01 * level.offset[t + 1];
          if (r1 >= 0) bs[r1 - first] += p01 * level.offset[t] + p11 * level.offset[t + 1];
          if (r0 >= 0 && r1 >= 0)
            blocks.push_back({r0 - first, r1 - first, p00, p01, p11});
          else if (r0 >= 0)
            blocks.push_back({r0 - first, -1, p00, 0, 0});
          else
            blocks.push_back({r1 - first, -1, p11, 0, 0});
        }
      }
      PetscCall(VecRestoreArrayRead(x, &xs));
      PetscCall(VecRestoreArray(b_step, &bs));
      solver.mask.couple(std::move(blocks));
      solver.mask.pin(std::move(pins));
      b = b_step;
    }
    PetscCall(solver.mask.system(b, values, x, rhs));
    double force = b_norm;
    for (double value : mu) force = std::max(force, std::abs(value));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &force, 1, MPI_DOUBLE, MPI_MAX, comm));
    const double final_target = kInnerFraction * settings.tol * (force > 0 ? force : 1.0);
    const bool solved_tight = tight;
    PetscInt iterations = 0;
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    PetscCall(solver.solve(rhs, x, final_target, solved_tight ? 0.0 : settings.loose_reduction, &iterations, &reason));
    outcome->krylov_iterations += iterations;
    outcome->steps = k;
    if (reason < 0) {
      outcome->status = Status::NumericalError;
      outcome->message = reason_text(solver.ksp, iterations, final_target);
      break;
    }
    // μ = b − A x on the active bounds (the force that holds them), 0 on the others.
    PetscCall(MatMult(level.A, x, Ax));
    std::vector<char> next(m, 0);
    TangentialStates next_states;
    {
      const PetscScalar *bv = nullptr, *ax = nullptr, *xs = nullptr;
      PetscCall(VecGetArrayRead(level.b, &bv));
      PetscCall(VecGetArrayRead(Ax, &ax));
      PetscCall(VecGetArrayRead(x, &xs));
      bool finite = true;
      for (std::size_t i = 0; i < m; ++i) {
        const PetscInt r = level.bounded[i] - first;
        mu[i] = active[i] ? bv[r] - ax[r] : 0.0;
        next[i] = mu[i] + diagonal[i] * (xs[r] - level.upper[i]) > 0;
        finite = finite && std::isfinite(mu[i]) && std::isfinite(xs[r]);
      }
      if (nd) {
        // λ_T = b − A x where the row sticks, r n where it slips; then the next state from z.
        next_states.stick.assign(n_rows, 0);
        next_states.direction.assign(n_tangential, 0.0);
        next_states.beta.assign(n_rows, 0.0);
        states->lambda_t.assign(n_tangential, 0.0);
        for (std::size_t j = 0; j < n_rows; ++j) {
          double z[3] = {0, 0, 0}, norm = 0;
          for (int d = 0; d < nd; ++d) {
            const std::size_t t = j * nd + d;
            if (level.tangential[t] < 0) continue;  // no free DOF: slip 0, λ_T 0
            const PetscInt r = level.tangential[t] - first;
            states->lambda_t[t] =
                states->stick[j] || pinned[j] ? bv[r] - ax[r] : level.radius[j] * states->direction[t];
            finite = finite && std::isfinite(states->lambda_t[t]) && std::isfinite(xs[r]);
          }
          // 3D slip: λ_T = r n + β P w (the step's linearised force).
          if (nd == 2 && !states->stick[j] && !pinned[j] && states->beta[j] > 0) {
            const std::size_t t = j * nd;
            const double n0 = states->direction[t], n1 = states->direction[t + 1];
            double w[2] = {0, 0};
            for (int d = 0; d < nd; ++d)
              if (level.tangential[t + d] >= 0) w[d] = xs[level.tangential[t + d] - first] - level.offset[t + d];
            const double along = n0 * w[0] + n1 * w[1];
            for (int d = 0; d < nd; ++d)
              if (level.tangential[t + d] >= 0)
                states->lambda_t[t + d] += states->beta[j] * (w[d] - along * states->direction[t + d]);
          }
          // One weight c per row, A's diagonal averaged over its directions: with a weight per
          // direction, z ∥ n would not make λ_T ∥ w, and the loop would stop short of the answer.
          double weight = 0;
          int counted = 0;
          for (int d = 0; d < nd; ++d)
            if (level.tangential[j * nd + d] >= 0) {
              weight += tangential_diagonal[j * nd + d];
              ++counted;
            }
          const double diagonal_mean = counted > 0 ? weight / counted : 0.0;
          for (int d = 0; d < nd; ++d) {
            const std::size_t t = j * nd + d;
            if (level.tangential[t] < 0) continue;
            const PetscInt r = level.tangential[t] - first;
            z[d] = states->lambda_t[t] + kTangentialWeight * diagonal_mean * (xs[r] - level.offset[t]);
            norm += z[d] * z[d];
          }
          norm = std::sqrt(norm);
          next_states.stick[j] = level.radius[j] > 0 && norm <= level.radius[j];
          if (!next_states.stick[j] && norm > 0)
            for (int d = 0; d < nd; ++d) next_states.direction[j * nd + d] = z[d] / norm;
          if (pinned[j] && !next_states.stick[j]) {
            // A pinned row turns by its force across n, λ_m, over (r + c‖w‖): with c = A's
            // diagonal (≥ the row's own stiffness, a Schur complement of A) the turn never
            // overshoots the answer's, and falls short by at most 1/(1 + kNewtonBound).
            double turned[2] = {0, 0}, length = 0;
            for (int d = 0; d < nd; ++d) {
              const std::size_t t = j * nd + d;
              if (level.tangential[t] < 0) continue;
              turned[d] = states->lambda_t[t] + diagonal_mean * (xs[level.tangential[t] - first] - level.offset[t]);
              length += turned[d] * turned[d];
            }
            length = std::sqrt(length);
            if (length > 0)
              for (int d = 0; d < nd; ++d) next_states.direction[j * nd + d] = turned[d] / length;
          }
          if (nd == 2 && !next_states.stick[j] && counted > 0 && norm > level.radius[j] && level.radius[j] > 0)
            next_states.beta[j] = kTangentialWeight * diagonal_mean * level.radius[j] / (norm - level.radius[j]);
        }
      }
      PetscCall(VecRestoreArrayRead(x, &xs));
      PetscCall(VecRestoreArrayRead(Ax, &ax));
      PetscCall(VecRestoreArrayRead(level.b, &bv));
      int all_finite = finite ? 1 : 0;
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &all_finite, 1, MPI_INT, MPI_MIN, comm));
      if (!all_finite) {
        outcome->status = Status::NumericalError;
        outcome->message = "the PETSc KSP returned a solution that is not finite";
        break;
      }
    }
    outcome->residual = nd ? settings.friction_residual(x, mu, states->lambda_t) : settings.residual(x, mu);
    long long changes = 0;
    for (std::size_t i = 0; i < m; ++i) changes += next[i] != active[i];
    for (std::size_t j = 0; j < n_rows; ++j)
      changes += next_states.stick[j] != states->stick[j] ||
                 (nd == 1 && !next_states.stick[j] && next_states.direction[j] * states->direction[j] <= 0);
    const bool settled = count_over_ranks(changes, comm) == 0;
    const bool repeats = !settled && seen.count(fingerprint(next, level.bounded, comm, friction, &next_states)) > 0;
    if (!settings.final_steps && (outcome->residual <= settings.tol || settled || repeats)) {
      outcome->status = Status::Converged;
      active = next;
      break;
    }
    if (!solved_tight && (outcome->residual <= settings.tol || settled || repeats)) {
      // Settled, or cycling, at a loose step: the same active set again at the final rule.
      tight = true;
      seen.clear();
      if (k >= settings.max_iterations) {
        outcome->status = Status::MaxIterations;
        outcome->message =
            "stopped after " + std::to_string(k) + " active-set steps with residual " + number_text(outcome->residual);
        break;
      }
      continue;
    }
    if (outcome->residual <= settings.tol) {
      outcome->status = Status::Converged;
      break;
    }
    // 3D: the slip directions are Newton's unknowns, not a set: with the sets settled (or
    // revisited while the directions move) the steps go on while the residual falls.
    if (nd == 2 && (settled || repeats)) {
      if (outcome->residual < 0.5 * best_tight) {
        best_tight = outcome->residual;
        stalled_steps = 0;
      } else if (++stalled_steps >= kStalledSteps) {
        outcome->status = Status::NumericalError;
        outcome->message = "the Newton steps on the slip directions stalled at residual " +
                           number_text(outcome->residual) + " (friction: try --backend active_set)";
        break;
      }
    } else if (settled) {
      outcome->status = Status::NumericalError;
      outcome->message = "the active set settled with residual " + number_text(outcome->residual) +
                         " above tol: the inner KSP solves are not accurate enough (a smaller -ksp_rtol may help)";
      break;
    }
    if (repeats && nd != 2) {
      outcome->status = Status::NumericalError;
      outcome->message =
          "the active-set steps cycled at residual " + number_text(outcome->residual) +
          (nd ? std::string(" (friction: try --backend active_set)") : " (try --backend-option method=tao)");
      break;
    }
    if (k >= settings.max_iterations) {
      outcome->status = Status::MaxIterations;
      outcome->message =
          "stopped after " + std::to_string(k) + " active-set steps with residual " + number_text(outcome->residual);
      break;
    }
    active = std::move(next);
    if (nd) {
      states->stick = std::move(next_states.stick);
      states->direction = std::move(next_states.direction);
      states->beta = std::move(next_states.beta);
    }
  }
  PetscCall(VecDestroy(&rhs));
  PetscCall(VecDestroy(&Ax));
  if (b_step) PetscCall(VecDestroy(&b_step));
  PetscFunctionReturn(0);
}

// The P1 start: the contact problem on the P1 level (PᵀAP, Pᵀb, a bound at each candidate
// vertex), solved loosely with the AMG of that level; then x = P x₁ and the fine active set
// where x reaches its bound. Returns false in *used when the problem has no P1 bounds.
PetscErrorCode p1_start(const PetscBoundQp& qp, const FineState& fine, const BoundPdasOptions& options, Vec x,
                        std::vector<char>& active, BoundPdasResult* result) {
  PetscFunctionBeginUser;
  PC amg = p1_level_preconditioner(fine.inner);
  const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(qp.A));
  long long n_bounds = 0;
  for (PetscInt column : qp.coarse_bounded) n_bounds += column >= 0;
  if (!amg || !fine.P1_operator || count_over_ranks(n_bounds, comm) == 0) PetscFunctionReturn(0);
  Stopwatch clock;
  LevelProblem level;
  level.A = fine.P1_operator;
  PetscCall(MatCreateVecs(level.A, &level.b, nullptr));
  PetscCall(MatMultTranspose(qp.coarse_interpolation, qp.b, level.b));
  PetscInt first = 0, end = 0;
  PetscCall(MatGetOwnershipRange(level.A, &first, &end));
  std::vector<std::pair<PetscInt, double>> bounds;
  for (std::size_t i = 0; i < qp.bounded.size(); ++i) {
    const PetscInt column = qp.coarse_bounded[i];
    // A candidate vertex's P1 columns are on its own rank (the seam with the data's owner).
    if (column >= first && column < end) bounds.emplace_back(column, qp.upper[i]);
  }
  std::sort(bounds.begin(), bounds.end());
  for (const auto& [column, upper] : bounds) {
    level.bounded.push_back(column);
    level.upper.push_back(upper);
  }
  LevelSolver solver;
  PetscCall(solver.create(level.A, amg, "contactqp_p1_"));
  LoopSettings settings;
  settings.tol = kP1Tolerance;
  settings.max_iterations = options.max_iterations;
  settings.inexact = true;
  settings.loose_reduction = options.loose_reduction;
  settings.final_steps = false;
  // The P1 problem's own residual: primal violation, negative multipliers and complementarity
  // over its scales, as the fine one's but on P1 data.
  settings.residual = [&level, comm](Vec v, const std::vector<double>& mu) {
    PetscInt start = 0;
    MatGetOwnershipRange(level.A, &start, nullptr);
    const PetscScalar* xs = nullptr;
    VecGetArrayRead(v, &xs);
    double violation = 0, negative = 0, complementarity = 0, length = 0, force = 0;
    for (std::size_t i = 0; i < level.bounded.size(); ++i) {
      const double slack = xs[level.bounded[i] - start] - level.upper[i];
      violation = std::max(violation, slack);
      negative = std::max(negative, -mu[i]);
      complementarity = std::max(complementarity, std::abs(std::max(mu[i], 0.0) * slack));
      length = std::max(length, std::abs(xs[level.bounded[i] - start]));
      force = std::max(force, std::abs(mu[i]));
    }
    VecRestoreArrayRead(v, &xs);
    PetscReal b_norm = 0, v_norm = 0;
    VecNorm(level.b, NORM_INFINITY, &b_norm);
    VecNorm(v, NORM_INFINITY, &v_norm);
    double values[5] = {violation, negative, complementarity, std::max(length, static_cast<double>(v_norm)),
                        std::max(force, static_cast<double>(b_norm))};
    MPI_Allreduce(MPI_IN_PLACE, values, 5, MPI_DOUBLE, MPI_MAX, comm);
    const double L = values[3] > 0 ? values[3] : 1.0, F = values[4] > 0 ? values[4] : 1.0;
    return std::max({values[0] / L, values[1] / F, values[2] / (F * L)});
  };
  Vec x1 = nullptr;
  PetscCall(VecDuplicate(level.b, &x1));
  PetscCall(VecSet(x1, 0.0));
  std::vector<char> active1(level.bounded.size(), 0);
  std::vector<double> mu1;
  LoopOutcome outcome;
  PetscCall(active_set_loop(level, solver, nullptr, settings, x1, active1, mu1, &outcome));
  result->p1_steps = outcome.steps;
  result->p1_krylov_iterations = outcome.krylov_iterations;
  if (outcome.status == Status::Converged || outcome.status == Status::MaxIterations) {
    // The fine iterate and active set: where the interpolated P1 answer reaches a bound (the
    // candidate vertices that hold it, exactly; mid-edge nodes between them, which the P1
    // chord pushes through the bound).
    PetscCall(MatMult(qp.coarse_interpolation, x1, x));
    PetscInt fine_first = 0;
    PetscCall(MatGetOwnershipRange(qp.A, &fine_first, nullptr));
    const PetscScalar* xs = nullptr;
    PetscCall(VecGetArrayRead(x, &xs));
    for (std::size_t i = 0; i < qp.bounded.size(); ++i) {
      const double value = xs[qp.bounded[i] - fine_first], upper = qp.upper[i];
      active[i] = value - upper >= -kRoundOff * std::max(std::abs(value), std::abs(upper));
    }
    PetscCall(VecRestoreArrayRead(x, &xs));
  }
  PetscCall(VecDestroy(&x1));
  PetscCall(VecDestroy(&level.b));
  result->p1_seconds = clock.seconds();
  PetscFunctionReturn(0);
}

}  // namespace

BoundPdasResult::BoundPdasResult(BoundPdasResult&& other) noexcept { *this = std::move(other); }

BoundPdasResult& BoundPdasResult::operator=(BoundPdasResult&& other) noexcept {
  if (this == &other) return *this;
  if (v && !petsc_finalized()) VecDestroy(&v);
  status = other.status;
  message = std::move(other.message);
  v = other.v;
  other.v = nullptr;
  mu = std::move(other.mu);
  lambda_t = std::move(other.lambda_t);
  stick = other.stick;
  slip = other.slip;
  iterations = other.iterations;
  krylov_iterations = other.krylov_iterations;
  linear_solves = other.linear_solves;
  p1_steps = other.p1_steps;
  p1_krylov_iterations = other.p1_krylov_iterations;
  preconditioner_setups = other.preconditioner_setups;
  active = other.active;
  active_bounds = std::move(other.active_bounds);
  residual = other.residual;
  setup_seconds = other.setup_seconds;
  iterate_seconds = other.iterate_seconds;
  p1_seconds = other.p1_seconds;
  update_seconds = other.update_seconds;
  multigrid = other.multigrid;
  method = std::move(other.method);
  solver_of_A = std::move(other.solver_of_A);
  return *this;
}

BoundPdasResult::~BoundPdasResult() {
  if (v && !petsc_finalized()) VecDestroy(&v);
}

namespace {

// The hierarchy on A and the loop's KSP around it, once per A (the set-up of solve_bound_pdas).
PetscErrorCode set_up_hierarchy(const PetscBoundQp& qp, const BoundPdasOptions& options, FineState* fine,
                                BoundPdasResult* result, bool* options_error) {
  PetscFunctionBeginUser;
  const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(qp.A));
  // The hierarchy on A, once; its finest smoother works on the step's W (the shell), its
  // Jacobi and the rest on A.
  PetscCall(fine->level.mask.create(qp.A));
  PetscCall(PCCreate(comm, &fine->inner));
  PetscCall(PCSetOperators(fine->inner, fine->level.mask.smoother_op(), qp.A));
  PetscCall(PCSetUseAmat(fine->inner, PETSC_TRUE));
  MultigridData data;
  data.A = qp.A;
  data.coarse_interpolation = qp.coarse_interpolation;
  data.coarse_modes = qp.coarse_modes;
  if (PetscErrorCode code = set_up_multigrid(fine->inner, data, &fine->P1_operator, &result->multigrid)) {
    *options_error = true;
    PetscFunctionReturn(code);
  }
  // The finest level's Chebyshev bounds from A itself (an empty mask), so that they hold for
  // every W: one application now, before any row is fixed.
  {
    Vec r = nullptr, z = nullptr;
    PetscCall(MatCreateVecs(qp.A, &z, &r));
    PetscCall(VecSet(r, 1.0));
    PetscCall(PCApply(fine->inner, r, z));
    PetscCall(VecDestroy(&r));
    PetscCall(VecDestroy(&z));
  }
  // The loop's KSP on W, around the masked hierarchy (LevelSolver::create without a second
  // mask: the fine level's mask is the one the hierarchy's smoother sees).
  {
    LevelSolver& level = fine->level;
    PetscCall(MatNorm(qp.A, NORM_INFINITY, &level.rule.A_norm));
    PetscCall(KSPCreate(comm, &level.ksp));
    PetscCall(KSPSetType(level.ksp, KSPCG));
    PetscCall(KSPSetOperators(level.ksp, level.mask.op(), qp.A));
    PetscCall(KSPSetNormType(level.ksp, KSP_NORM_UNPRECONDITIONED));
    PetscCall(KSPSetTolerances(level.ksp, 0.0, 0.0, PETSC_DEFAULT, kMaxKrylovIterations));
    PetscCall(KSPConvergedDefaultCreate(&level.rule.default_test));
    PetscCall(KSPSetConvergenceTest(level.ksp, StoppingRule::test, &level.rule, nullptr));
    PC outer = nullptr;
    PetscCall(KSPGetPC(level.ksp, &outer));
    PetscCall(level.mask.wrap(outer, fine->inner));
    PetscCall(PCSetOptionsPrefix(outer, "contactqp_masked_"));
    if (PetscErrorCode code = KSPSetFromOptions(level.ksp)) {
      *options_error = true;
      PetscFunctionReturn(code);
    }
    PetscCall(KSPSetInitialGuessNonzero(level.ksp, PETSC_TRUE));
  }
  if (options.truncate) PetscCall(fine->truncation.collect(fine->inner, qp.A));
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode solve_bound_pdas(const PetscBoundQp& qp, const BoundPdasOptions& options, BoundPdasResult* result,
                                bool* options_error, const WarmStart* start) {
  PetscFunctionBeginUser;
  *options_error = false;
  const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(qp.A));
  // A load step after another on the same A: that solve's hierarchy, KSP and answer.
  const auto kept = start ? std::dynamic_pointer_cast<KeptSolverOfA>(start->solver_of_A) : nullptr;
  const bool warm = kept && start->v && start->active_bounds.size() == qp.bounded.size();
  Stopwatch clock;
  std::shared_ptr<FineState> fine;
  if (warm) {
    fine = kept->state();
    result->multigrid = start->multigrid;
  } else {
    fine = std::make_shared<FineState>();
    fine->tol = options.tol;
    PetscCall(set_up_hierarchy(qp, options, fine.get(), result, options_error));
    result->preconditioner_setups = 1;
  }
  result->setup_seconds = clock.seconds();

  clock.restart();
  PetscCall(MatCreateVecs(qp.A, &result->v, nullptr));
  std::vector<char> active(qp.bounded.size(), 0);
  if (warm) {
    PetscCall(VecCopy(start->v, result->v));
    active = start->active_bounds;
  } else if (qp.start_active.size() == qp.bounded.size() && !qp.start_active.empty()) {
    PetscCall(VecSet(result->v, 0.0));
    active = qp.start_active;
  } else {
    PetscCall(VecSet(result->v, 0.0));
    // The P1 start knows the bounds only: with friction the fine loop starts from zero.
    if (options.p1_start && qp.n_directions == 0 && qp.coarse_interpolation &&
        qp.coarse_bounded.size() == qp.bounded.size())
      PetscCall(p1_start(qp, *fine, options, result->v, active, result));
  }

  LevelProblem level;
  level.A = qp.A;
  level.b = qp.b;
  level.bounded = qp.bounded;
  level.upper = qp.upper;
  level.n_directions = qp.n_directions;
  level.tangential = qp.tangential;
  level.offset = qp.offset;
  level.radius = qp.radius;
  // Every contact row starts sticking where it has a friction force (r > 0), else slipping
  // freely (λ_T = 0): the frictionless problem's first step.
  TangentialStates states;
  const bool friction = qp.n_directions > 0;
  if (friction) {
    states.stick.resize(qp.radius.size());
    for (std::size_t j = 0; j < qp.radius.size(); ++j) states.stick[j] = qp.radius[j] > 0;
    states.direction.assign(qp.tangential.size(), 0.0);
    states.beta.assign(qp.radius.size(), 0.0);
    if (qp.start_stick.size() == qp.radius.size() && qp.start_direction.size() == qp.tangential.size()) {
      states.stick = qp.start_stick;
      states.direction = qp.start_direction;
    }
  }
  LoopSettings settings;
  settings.tol = options.tol;
  settings.max_iterations = options.max_iterations;
  settings.inexact = options.inexact;
  settings.loose_reduction = options.loose_reduction;
  settings.residual = options.residual;
  settings.friction_residual = options.friction_residual;
  LoopOutcome outcome;
  PetscCall(active_set_loop(level, fine->level, fine->truncation.active() ? &fine->truncation : nullptr, settings,
                            result->v, active, result->mu, &outcome, friction ? &states : nullptr));
  fine->level.mask.couple({});
  fine->level.mask.pin({});
  if (friction) {
    result->lambda_t = std::move(states.lambda_t);
    result->stick = count_over_ranks(std::count(states.stick.begin(), states.stick.end(), 1), comm);
    long long slipping = 0;
    for (std::size_t j = 0; j < states.stick.size(); ++j) slipping += !states.stick[j] && qp.radius[j] > 0;
    result->slip = count_over_ranks(slipping, comm);
  }
  for (double& value : result->mu) value = std::max(value, 0.0);
  result->status = outcome.status;
  result->message = outcome.message;
  result->iterations = outcome.steps;
  result->krylov_iterations = outcome.krylov_iterations;
  result->linear_solves = outcome.steps;
  result->residual = outcome.residual;
  result->active = count_over_ranks(std::count(active.begin(), active.end(), 1), comm);
  result->active_bounds = active;
  result->update_seconds = fine->truncation.update_seconds();
  result->iterate_seconds = clock.seconds();
  result->method = "pdas, cg + " + result->multigrid.method + (result->p1_steps > 0 ? ", P1 start" : "") +
                   (fine->truncation.active() ? ", truncated" : "");
  result->solver_of_A = std::make_shared<KeptSolverOfA>(fine);
  PetscFunctionReturn(0);
}

}  // namespace contactqp::detail
