#include "uzawa_common.hpp"

#include <algorithm>
#include <cmath>

#include "backend_options.hpp"
#include "contactqp/backends/uzawa.hpp"
#include "contactqp/certificate.hpp"
#include "contactqp/number_format.hpp"
#include "coulomb_fixed_point.hpp"
#include "qp/norms.hpp"

namespace contactqp::detail {
namespace {

// How many iterations without progress (DivergenceGuard) count as not converging, at the
// automatic step or above.
constexpr double kStallWindow = 200;
// A residual or a step this many times above the smallest one seen means the iteration is expanding.
constexpr double kGrowthFactor = 1e6;
// Relative decrease of the step below which it counts as round-off, not progress.
constexpr double kRoundOff = 1e-12;
// A row switched on and off on this many consecutive iterations is in a 2-cycle...
constexpr int kFlipWindow = 50;
// ... unless its positive value is below this fraction of ‖λ‖∞ (a row with λ_i = 0 at the
// optimum and no gap may be switched by a decaying error, which is convergence, not a cycle).
constexpr double kFlipFloor = 1e-3;

// Whether row i of C has an entry. T has zero rows where a node's tangential DOFs are
// prescribed: S is 0 there, and such a row in the working set would make λ_min(S_R) = 0 and
// ρ_opt = ρ_max, where plain Uzawa stops contracting.
std::vector<bool> nonzero_rows(const MultiplierSet& set) {
  std::vector<bool> nonzero(set.rows(), false);
  const SparseMatrix& C = set.C();
  for (int j = 0; j < C.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(C, j); it; ++it)
      if (it.value() != 0) nonzero[it.row()] = true;
  return nonzero;
}

// The rows the unconstrained solution violates, and with friction every (nonzero) tangential
// row: the working set of the spectrum estimate.
std::vector<int> violated_rows(const QuadraticProgram& qp, const MultiplierSet& set, const VectorXd& u_free) {
  const VectorXd r = qp.B * u_free - qp.g;
  std::vector<int> rows;
  for (int i = 0; i < r.size(); ++i)
    if (r[i] > 0) rows.push_back(i);
  if (set.frictional()) {
    const std::vector<bool> nonzero = nonzero_rows(set);
    for (int i = set.normal_rows(); i < set.rows(); ++i)
      if (nonzero[i]) rows.push_back(i);
  }
  return rows;
}

// "Every row" for the spectrum: {} (all of C) unless C has zero rows (friction only), then the others.
std::vector<int> every_row(const MultiplierSet& set) {
  if (!set.frictional()) return {};
  const std::vector<bool> nonzero = nonzero_rows(set);
  std::vector<int> rows;
  for (int i = 0; i < set.rows(); ++i)
    if (nonzero[i]) rows.push_back(i);
  if (static_cast<int>(rows.size()) == set.rows()) rows.clear();
  return rows;
}

// The step from the spectrum of S on `rows` (every row when empty), by the rule of `uzawa`.
// Plain Uzawa's automatic step is ρ_opt = 2/(λ_min + λ_max), which minimises
// max |1 − ρμ| over the spectrum; the accelerated iteration needs a step of at most 1/λ_max
// (Nesterov/FISTA's 1/L), i.e. ρ_max/2.
UzawaStep choose_step(const MultiplierSet& set, const LinearSolver& K_factor, const UzawaOptions& uzawa,
                      UzawaVariant variant, const std::vector<int>& rows) {
  UzawaStep step;
  step.all_rows = rows.empty();
  if (set.rows() > 0) step.spectrum = estimate_spectrum(set.C(), K_factor, rows);
  const SpectrumEstimate& s = step.spectrum;
  if (s.lambda_max > 0) {
    step.rho_max = 2.0 / s.lambda_max;
    step.rho_opt = 2.0 / (s.lambda_min + s.lambda_max);
  }
  const bool known = std::isfinite(step.rho_max);
  switch (uzawa.rho_rule) {
    case UzawaOptions::RhoRule::Auto:
      // Without a spectrum (no rows) there is no iteration for the step to change.
      step.rho = !known ? 1.0 : variant == UzawaVariant::Plain ? step.rho_opt : 0.5 * step.rho_max;
      break;
    case UzawaOptions::RhoRule::Absolute:
      step.rho = uzawa.rho;
      break;
    case UzawaOptions::RhoRule::FractionOfMax:
      step.rho = known ? uzawa.rho * step.rho_max : uzawa.rho;
      break;
  }
  // The iterates move by about ρ times the gradient per iteration, so a stretch without
  // progress is measured in ρ·k: below the automatic step the window grows as 1/ρ. With 200
  // iterations at --rho 1e-6x, the accelerated iteration was declared diverged at iteration
  // 5 819 while converging (its residual 2e-2 after a change of the contact set, 9e-8 before).
  if (known) {
    const double automatic = variant == UzawaVariant::Plain ? step.rho_opt : 0.5 * step.rho_max;
    step.stall_window = kStallWindow * std::max(1.0, automatic / step.rho);
  }
  return step;
}

void record_step(const UzawaStep& step, int spectrum_solves, SolveResult& result) {
  auto& d = result.diagnostics;
  d["rho"] = step.rho;
  d["rho_max"] = step.rho_max;  // erased by solve() when not finite (no rows)
  d["rho_opt"] = step.rho_opt;
  d["lambda_max_S"] = step.spectrum.lambda_max;
  d["lambda_min_S"] = step.spectrum.lambda_min;
  d["spectrum_rows"] = step.spectrum.rows;
  d["spectrum_all_rows"] = step.all_rows ? 1 : 0;
  d["spectrum_converged"] = step.spectrum.converged ? 1 : 0;
  d["spectrum_solves"] = spectrum_solves;
}

std::string closing_message(const SolveOptions& options, UzawaVariant variant, const UzawaStep& step,
                            const UzawaRun& run, bool fell_back) {
  // The backend sees a scaled QP: quote ρ in the caller's units.
  const double unit = options.get<UzawaOptions>().rho_unit;
  const bool known = std::isfinite(step.rho_max);
  const std::string rho =
      "ρ = " + short_number(step.rho * unit) + (known ? " (" + short_number(step.rho / step.rho_max) + " ρ_max)" : "");
  const std::string rho_max = known ? "ρ_max = 2/λ_max(S) ≈ " + short_number(step.rho_max * unit) : "no ρ_max (S = 0)";
  const std::string note =
      fell_back ? "; the step from the violated rows did not converge, so ρ was re-chosen from every row" : "";
  switch (run.status) {
    case Status::Converged:
      return "converged: relative change of λ and primal violation below " + short_number(options.tol) + note;
    case Status::MaxIterations:
      return "stopped after " + std::to_string(run.iterations) + " iterations at relative residual " +
             short_number(run.residual) + " (best " + short_number(run.best_residual) + ", tol " +
             short_number(options.tol) + ") with " + rho + "; " +
             (known ? "a larger ρ (up to " + rho_max + ")" : "a larger ρ") + " or more iterations may help" + note;
    case Status::Diverged:
      return "diverged after " + std::to_string(run.iterations) + " iterations: " + rho + " is too large (" + rho_max +
             (variant == UzawaVariant::Accelerated ? "; the accelerated iteration needs about ρ ≤ ρ_max/2" : "") +
             "); use --rho auto or a smaller ρ" + note;
    default:  // NumericalError; the rest are solve()'s, from the certificate
      break;
  }
  return "numerical error";
}

}  // namespace

double uzawa_residual(const MultiplierSet& set, const VectorXd& u, const VectorXd& r, const VectorXd& lambda_from,
                      const VectorXd& lambda_next) {
  const double change = inf_norm(lambda_next - lambda_from);
  const double lambda_size = inf_norm(lambda_next);
  const double rel_change = lambda_size > 0 ? change / lambda_size : change;
  // certify()'s length scale without friction, max(‖u‖∞, ‖Bu‖∞); with it ‖Tu‖∞ joins.
  const double L = std::max(inf_norm(u), inf_norm(VectorXd(set.C() * u)));
  const int m = set.normal_rows();  // r's first m entries are B u − g; the rest, with friction, the slip
  const double violation = m ? std::max(0.0, r.head(m).maxCoeff()) : 0.0;
  const double rel_violation = L > 0 ? violation / L : violation;
  return std::max(rel_change, rel_violation);
}

DivergenceGuard::Verdict DivergenceGuard::check(int k, double residual, const VectorXd& lambda_from,
                                                const VectorXd& lambda_next) {
  if (!lambda_next.allFinite() || !std::isfinite(residual)) return Verdict::Diverged;
  const double step = (lambda_next - lambda_from).norm();
  last_residual_ = residual;
  // A step smaller by round-off only is no progress: a 2-cycle repeats its steps exactly.
  if (residual < best_residual_) last_residual_progress_ = k;
  if (step < (1 - kRoundOff) * best_step_) last_step_progress_ = k;
  best_residual_ = std::min(best_residual_, residual);
  best_step_ = std::min(best_step_, step);
  if (residual <= tol_) return Verdict::Converged;
  if (residual > kGrowthFactor * best_residual_ || step > kGrowthFactor * best_step_) return Verdict::Diverged;

  const double negligible = kFlipFloor * std::max(inf_norm(lambda_from), inf_norm(lambda_next));
  bool alternating = false;
  for (size_t i = 0; i < flips_.size(); ++i) {
    const bool flip =
        (lambda_next[i] > 0) != (lambda_from[i] > 0) && std::max(lambda_next[i], lambda_from[i]) > negligible;
    flips_[i] = flip ? flips_[i] + 1 : 0;
    alternating = alternating || flips_[i] >= kFlipWindow;
  }
  // A cycle that is still decaying (the residual keeps improving) is a transient, not divergence.
  if (alternating && k - last_residual_progress_ >= kFlipWindow) return Verdict::Diverged;
  if (k - std::max(last_residual_progress_, last_step_progress_) > stall_window_) return Verdict::Diverged;
  return Verdict::Continue;
}

IterationMonitor::IterationMonitor(const UzawaContext& context, const UzawaStep& step, int first_k, UzawaRun& run)
    : context_(context),
      first_k_(first_k),
      run_(run),
      guard_(context.options.tol, context.qp.n_constraints(), step.stall_window) {
  run_.u = context.u_start;
  run_.lambda = context.lambda_start;
}

bool IterationMonitor::stop(int k, const VectorXd& u, const VectorXd& r, const VectorXd& lambda_from,
                            const VectorXd& lambda_next) {
  // A failed solve with K (an iterative solver that did not converge) ends the run; the
  // iterate returned is the last one computed from a good solve.
  if (!context_.K_factor.ok()) {
    run_.status = Status::NumericalError;
    return true;
  }
  const double residual = uzawa_residual(context_.set, u, r, lambda_from, lambda_next);
  if (context_.options.observer)
    context_.options.observer(first_k_ + k + 1, u,
                              context_.set.frictional() ? context_.set.lambda(lambda_from) : lambda_from);
  const DivergenceGuard::Verdict verdict = guard_.check(k, residual, lambda_from, lambda_next);
  if (verdict == DivergenceGuard::Verdict::Diverged) {
    run_.status = Status::Diverged;
    return true;
  }
  run_.u = u;
  run_.lambda = lambda_from;
  if (verdict == DivergenceGuard::Verdict::Converged) {
    run_.status = Status::Converged;
    return true;
  }
  return false;
}

void IterationMonitor::finish(int k) {
  run_.iterations = k + (run_.status == Status::Converged ? 1 : 0);
  run_.residual = guard_.last();
  run_.best_residual = guard_.best();
}

SolveResult run_uzawa(const QuadraticProgram& qp, const VectorXd& radii, const SolveOptions& options,
                      UzawaVariant variant, UzawaLoop loop) {
  const MultiplierSet set(qp, radii);
  const VectorXd warm = initial_multipliers(qp, options, set);  // before any work: it checks sizes
  SolveResult result;
  result.K_factor = factor_of_K(qp, options, result.timings, result.message);
  if (!result.K_factor) return result;
  const LinearSolver& K_factor = *result.K_factor;
  const int m = qp.n_constraints();

  Stopwatch clock;
  const VectorXd u_free = K_factor.solve(qp.f);
  // The start: λ = 0 (u = K⁻¹f), or the warm start and its u (one solve more).
  const VectorXd lambda_start = warm.size() ? warm : VectorXd(VectorXd::Zero(set.rows()));
  const VectorXd u_start =
      warm.size() ? K_factor.solve(VectorXd(qp.f - set.C().transpose() * warm), options.initial.u) : u_free;
  double solve_seconds = clock.seconds();
  std::vector<int> working = violated_rows(qp, set, u_free);
  if (static_cast<int>(working.size()) == set.rows()) working.clear();  // every row: no sub-block
  const std::vector<int> all_rows = every_row(set);
  if (working.empty()) working = all_rows;

  const UzawaOptions uzawa = options.get<UzawaOptions>();
  UzawaStep step = choose_step(set, K_factor, uzawa, variant, working);
  if (!K_factor.ok()) {
    result.message = "a solve with K failed before the iteration: " + K_factor.message();
    result.u = u_free;
    result.lambda = VectorXd::Zero(m);
    result.lambda_t = set.lambda_t(VectorXd::Zero(set.rows()));
    return result;
  }
  double spectrum_seconds = step.spectrum.seconds;
  int spectrum_solves = step.spectrum.applications;

  const UzawaContext context{qp, K_factor, options, set, lambda_start, u_start};
  clock.restart();
  UzawaRun run = loop(context, step, 0, options.max_iterations);
  solve_seconds += clock.seconds();

  // The working-set step is not guaranteed (ρ_opt of the block may exceed 2/λ_max of all of
  // S, and rows outside the block may become active): with --rho auto a run that does not
  // converge starts again from its start with the step from every row, which is guaranteed.
  bool fell_back = false;
  const int remaining = options.max_iterations - run.iterations;
  if (run.status == Status::Diverged && uzawa.rho_rule == UzawaOptions::RhoRule::Auto &&
      step.spectrum.rows < static_cast<int>(all_rows.empty() ? set.rows() : all_rows.size()) && remaining > 0) {
    step = choose_step(set, K_factor, uzawa, variant, all_rows);
    spectrum_seconds += step.spectrum.seconds;
    spectrum_solves += step.spectrum.applications;
    clock.restart();
    UzawaRun second = loop(context, step, run.iterations, remaining);
    solve_seconds += clock.seconds();
    second.iterations += run.iterations;
    run = std::move(second);
    fell_back = true;
  }

  result.timings.add("spectrum", spectrum_seconds);
  result.timings.add("solve", solve_seconds);
  record_step(step, spectrum_solves, result);
  result.diagnostics["rho_fallback"] = fell_back ? 1 : 0;
  result.diagnostics["residual"] = run.residual;
  result.diagnostics["best_residual"] = run.best_residual;
  for (const auto& [name, value] : run.diagnostics) result.diagnostics[name] = value;
  result.status = run.status;
  result.iterations = run.iterations;
  result.message = run.status == Status::NumericalError ? "a solve with K failed at iteration " +
                                                              std::to_string(run.iterations) + ": " + K_factor.message()
                                                        : closing_message(options, variant, step, run, fell_back);
  result.u = std::move(run.u);
  result.lambda_t = set.lambda_t(run.lambda);  // none without friction; zeros when every radius is 0
  result.lambda = set.frictional() ? set.lambda(run.lambda) : std::move(run.lambda);
  return result;
}

SolveResult solve_uzawa_variant(const QuadraticProgram& qp, const SolveOptions& options, UzawaVariant variant,
                                UzawaLoop loop) {
  if (qp.friction.law != FrictionLaw::Coulomb) return run_uzawa(qp, qp.friction.threshold, options, variant, loop);
  // The step of the first frictional Tresca solve serves the later ones: S = C K⁻¹ Cᵀ does not
  // change with the radii.
  double rho = 0;
  return solve_coulomb_by_fixed_point(qp, options, [&](const VectorXd& radii, const SolveOptions& step_options) {
    SolveOptions fixed = step_options;
    if (rho > 0) {
      UzawaOptions step = fixed.get<UzawaOptions>();
      step.rho_rule = UzawaOptions::RhoRule::Absolute;
      step.rho = rho;
      fixed.set(step);
    }
    SolveResult result = run_uzawa(qp, radii, fixed, variant, loop);
    // Not from a solve whose radii are all 0: that one ran on B's rows alone (multiplier_set.hpp).
    const bool frictional = radii.size() > 0 && radii.cwiseAbs().maxCoeff() > 0;
    if (rho == 0 && frictional && result.status == Status::Converged) rho = result.diagnostics["rho"];
    return result;
  });
}

void check_uzawa_options(const SolveOptions& options) {
  reject_options(options.backend, options.backend_options,
                 "its step is --rho or solver.rho (address other backends' options as ipopt.key=value)");
}

}  // namespace contactqp::detail
