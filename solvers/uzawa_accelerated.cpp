// Accelerated Uzawa: Nesterov/FISTA extrapolation on the dual, with adaptive restart.
//
//   K u_k = f − Bᵀy_k                                   (one solve per iteration, as in Uzawa)
//   λ_{k+1} = max(0, y_k + ρ (B u_k − g))               (Uzawa's step, taken from y_k)
//   y_{k+1} = max(0, λ_{k+1} + β_k (λ_{k+1} − λ_k))     (extrapolation)
//
// β_k is FISTA's (t_k − 1)/t_{k+1}, t_{k+1} = (1 + √(1 + 4t_k²))/2, capped by the constant
// momentum of Nesterov's scheme for strongly concave duals, (1 − √(ρλ_min))/(1 + √(ρλ_min)),
// with λ_min(S) from the same Lanczos estimate that gives ρ: FISTA's momentum alone tends to 1
// and overshoots, which on a quadratic makes it ripple at the rate of plain Uzawa. The
// iteration needs ρ ≤ 1/λ_max(S) = ρ_max/2 (FISTA's 1/L), the automatic step.
//
// Adaptive restart (O'Donoghue & Candès 2015, gradient scheme): when the gradient mapping
// y_k − λ_{k+1} and the step λ_{k+1} − λ_k make an acute angle, the momentum points downhill
// for θ; the momentum is then reset (t = 1, y = λ_{k+1}). It needs no extra solve, unlike the
// function scheme, which would evaluate θ(λ_{k+1}).
//
// The extrapolated point is projected onto λ ≥ 0 (and with friction onto the discs,
// multiplier_set.hpp), so every (u_k, y_k) is a dual-feasible pair
// with u_k = u(y_k): the stopping rule, the observer and the certificate see what plain
// Uzawa's would, and the converged (u_k, y_k) is returned as it is.
#include <algorithm>
#include <cmath>

#include "uzawa_common.hpp"

namespace contactqp::detail {
namespace {

// The largest momentum worth using when λ_min(S) is known: Nesterov's constant β for a
// function with curvature in [λ_min, 1/ρ]. Without a positive λ_min the cap is inactive.
double momentum_cap(const UzawaStep& step) {
  const double q = step.rho * step.spectrum.lambda_min;
  if (!(q > 0)) return 1.0;
  if (q >= 1) return 0.0;
  return (1 - std::sqrt(q)) / (1 + std::sqrt(q));
}

UzawaRun accelerated_loop(const UzawaContext& context, const UzawaStep& step, int first_k, int max_iterations) {
  const QuadraticProgram& qp = context.qp;
  const MultiplierSet& set = context.set;
  UzawaRun run;
  IterationMonitor monitor(context, step, first_k, run);
  const double beta_cap = momentum_cap(step);
  VectorXd lambda = context.lambda_start;  // λ_k
  VectorXd y = lambda;                     // the extrapolated point y_k
  VectorXd u = context.u_start;
  double t = 1;
  int restarts = 0;
  int k = 0;
  for (; k < max_iterations; ++k) {
    if (k > 0) u = context.K_factor.solve(VectorXd(qp.f - set.C().transpose() * y), u);  // warm start, as in uzawa.cpp
    const VectorXd r = set.C() * u - set.c();
    const VectorXd lambda_next = set.project(y + step.rho * r);
    if (monitor.stop(k, u, r, y, lambda_next)) break;
    if ((y - lambda_next).dot(lambda_next - lambda) > 0) {
      t = 1;
      y = lambda_next;
      ++restarts;
    } else {
      const double t_next = 0.5 * (1 + std::sqrt(1 + 4 * t * t));
      const double beta = std::min((t - 1) / t_next, beta_cap);
      y = set.project(lambda_next + beta * (lambda_next - lambda));
      t = t_next;
    }
    lambda = lambda_next;
  }
  monitor.finish(k);
  run.diagnostics["restarts"] = restarts;
  run.diagnostics["momentum_cap"] = beta_cap;
  return run;
}

SolveResult solve_uzawa_accelerated(const QuadraticProgram& qp, const SolveOptions& options) {
  return solve_uzawa_variant(qp, options, UzawaVariant::Accelerated, accelerated_loop);
}

}  // namespace
}  // namespace contactqp::detail

CONTACTQP_BUILTIN(uzawa_accel) {
  BackendRegistration accelerated;
  accelerated.name = "uzawa_accel";
  accelerated.summary = "Uzawa with Nesterov extrapolation on the dual and adaptive restart";
  accelerated.order = 20;
  accelerated.check_options = check_uzawa_options;
  accelerated.solve = solve_uzawa_accelerated;
  accelerated.problem_kinds = {ProblemKind::Frictionless, ProblemKind::Tresca, ProblemKind::Coulomb};
  register_backend(accelerated);
}
