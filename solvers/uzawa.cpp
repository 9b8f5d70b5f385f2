// Uzawa's algorithm, the reference paper's method: projected gradient ascent on the dual.
//
//   K u_k = f − Bᵀλ_k                     (one solve with the factor of K, computed once)
//   λ_{k+1} = max(0, λ_k + ρ (B u_k − g))
//
// With S = B K⁻¹ Bᵀ it converges for 0 < ρ < ρ_max = 2/λ_max(S). The step, the stopping
// rule and the divergence guard are shared with the accelerated variant (uzawa_common.hpp).
#include "uzawa_common.hpp"

namespace contactqp::detail {
namespace {

UzawaRun plain_loop(const UzawaContext& context, const UzawaStep& step, int first_k, int max_iterations) {
  const QuadraticProgram& qp = context.qp;
  UzawaRun run;
  IterationMonitor monitor(context, step, first_k, run);
  VectorXd lambda = VectorXd::Zero(qp.n_constraints());
  VectorXd u = context.u_free;
  int k = 0;
  for (; k < max_iterations; ++k) {
    // Warm-started from the previous u: an iterative solver of K then starts close, as λ moves
    // less and less (a direct one ignores the guess).
    if (k > 0) u = context.K_factor.solve(VectorXd(qp.f - qp.B.transpose() * lambda), u);
    const VectorXd r = qp.B * u - qp.g;  // ≤ 0 where feasible
    const VectorXd lambda_next = (lambda + step.rho * r).cwiseMax(0.0);
    if (monitor.stop(k, u, r, lambda, lambda_next)) break;
    lambda = lambda_next;
  }
  monitor.finish(k);
  return run;
}

SolveResult solve_uzawa(const QuadraticProgram& qp, const SolveOptions& options) {
  return run_uzawa(qp, options, UzawaVariant::Plain, plain_loop);
}

}  // namespace
}  // namespace contactqp::detail

CONTACTQP_BUILTIN(uzawa) {
  BackendRegistration uzawa;
  uzawa.name = "uzawa";
  uzawa.summary = "dual projected gradient with a fixed step rho (the reference paper's method)";
  uzawa.order = 10;
  uzawa.check_options = check_uzawa_options;
  uzawa.solve = solve_uzawa;
  register_backend(uzawa);
}
