// Uzawa's algorithm, the reference paper's method: projected gradient ascent on the dual.
//
//   K u_k = f − Bᵀλ_k                     (one solve with the factor of K, computed once)
//   λ_{k+1} = max(0, λ_k + ρ (B u_k − g))
//
// With S = B K⁻¹ Bᵀ it converges for 0 < ρ < ρ_max = 2/λ_max(S).
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "backends.hpp"
#include "contactqp/certificate.hpp"
#include "spectrum.hpp"

namespace contactqp::detail {
namespace {

double inf_norm(const VectorXd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

std::string format(double x) {
  std::ostringstream out;
  out.precision(4);
  out << x;
  return out.str();
}

// How many iterations without a new best residual count as stalling: a bounded oscillation
// (ρ above ρ_max with the projection clipping the growth) never improves; a slow but
// converging iteration (ρ tiny) improves every step.
constexpr int kStallWindow = 200;
// A residual this many times above the best one seen means the iteration is expanding.
constexpr double kGrowthFactor = 1e6;

}  // namespace

SolveResult solve_uzawa(const QuadraticProgram& qp, const SolveOptions& options) {
  SolveResult result;
  const int m = qp.n_constraints();

  result.K_factor = factor_of_K(qp, options, result.timings, result.message);
  if (!result.K_factor) return result;
  const CholeskyFactor& K_factor = *result.K_factor;

  // The step ρ. ρ_max comes from λ_max(S), estimated even for a user's ρ so that the result
  // can say how the step compares with the limit. The power iteration approaches λ_max from
  // below, so the automatic step keeps a 10% margin under the estimated ρ_max.
  const UzawaOptions& uzawa = options.uzawa;
  double rho_max = std::numeric_limits<double>::infinity();
  if (m > 0) {
    const SpectrumEstimate spectrum = estimate_lambda_max(qp, K_factor);
    result.timings.add("spectrum", spectrum.seconds);
    result.diagnostics["spectrum_solves"] = spectrum.applications;
    if (spectrum.lambda_max > 0) {
      rho_max = 2.0 / spectrum.lambda_max;
      result.diagnostics["lambda_max_S"] = spectrum.lambda_max;
      result.diagnostics["rho_max"] = rho_max;
    }
  }
  double rho = 0;
  switch (uzawa.rho_rule) {
    case UzawaOptions::RhoRule::Auto: rho = std::isfinite(rho_max) ? 0.9 * rho_max : 1.0; break;
    case UzawaOptions::RhoRule::Absolute: rho = uzawa.rho; break;
    case UzawaOptions::RhoRule::FractionOfMax:
      rho = std::isfinite(rho_max) ? uzawa.rho * rho_max : uzawa.rho;
      break;
  }
  result.diagnostics["rho"] = rho;

  Stopwatch solve_clock;
  VectorXd lambda = VectorXd::Zero(m);
  VectorXd u = K_factor.solve(qp.f);
  double best_residual = std::numeric_limits<double>::infinity();
  int last_improvement = 0;
  result.status = Status::MaxIterations;

  int k = 0;
  for (; k < options.max_iterations; ++k) {
    if (k > 0) u = K_factor.solve(VectorXd(qp.f - qp.B.transpose() * lambda));
    const VectorXd r = qp.B * u - qp.g;  // ≤ 0 where feasible
    const VectorXd lambda_next = (lambda + rho * r).cwiseMax(0.0);

    // Stopping rule: the projected step changes λ little, relative to λ, and the primal
    // violation is small relative to the displacement.
    const double change = inf_norm(lambda_next - lambda);
    const double lambda_size = inf_norm(lambda_next);
    const double rel_change = lambda_size > 0 ? change / lambda_size : change;
    const double L = length_scale(qp, u);
    const double violation = r.size() ? std::max(0.0, r.maxCoeff()) : 0.0;
    const double rel_violation = L > 0 ? violation / L : violation;
    const double residual = std::max(rel_change, rel_violation);
    if (options.observer) options.observer(k + 1, u, lambda);

    if (!std::isfinite(residual) || !lambda_next.allFinite()) {
      result.status = Status::Diverged;
      break;
    }
    if (residual <= options.tol) {
      result.status = Status::Converged;
      break;
    }
    if (residual < best_residual) {
      best_residual = residual;
      last_improvement = k;
    } else if (residual > kGrowthFactor * best_residual || k - last_improvement > kStallWindow) {
      result.status = Status::Diverged;
      break;
    }
    lambda = lambda_next;
  }
  result.iterations = k + (result.status == Status::Converged ? 1 : 0);
  result.timings.add("solve", solve_clock.seconds());
  result.u = u;
  result.lambda = lambda;

  switch (result.status) {
    case Status::Converged:
      result.message = "converged: relative change of λ and primal violation below " + format(options.tol);
      break;
    case Status::MaxIterations:
      result.message = "stopped after " + std::to_string(options.max_iterations) +
                       " iterations with residual " + format(best_residual) +
                       "; a larger ρ (at most ρ_max = " + format(rho_max) + ") or more iterations may help";
      break;
    case Status::Diverged:
      result.message = "diverged after " + std::to_string(k) + " iterations: ρ = " + format(rho) +
                       " is too large (ρ_max = 2/λ_max(S) ≈ " + format(rho_max) + "); use --rho auto or a smaller ρ";
      break;
    case Status::NumericalError: break;
  }
  if (!u.allFinite() || !lambda.allFinite()) {
    // The last update overflowed: fall back to the multipliers that produced the last finite u.
    result.u = VectorXd::Zero(qp.n_dofs());
    result.lambda = VectorXd::Zero(m);
  }
  return result;
}

}  // namespace contactqp::detail
