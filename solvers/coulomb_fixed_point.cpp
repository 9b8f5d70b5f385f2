#include "coulomb_fixed_point.hpp"

#include "contactqp/number_format.hpp"
#include "qp/norms.hpp"

namespace contactqp::detail {

SolveResult solve_coulomb_by_fixed_point(const QuadraticProgram& qp, const SolveOptions& options,
                                         const TrescaSolve& tresca) {
  const VectorXd& mu = qp.friction.coefficient;
  const int m = qp.n_constraints();
  SolveOptions step_options = options;
  VectorXd radii = options.initial.lambda.size() == m ? VectorXd(mu.cwiseProduct(options.initial.lambda.cwiseMax(0.0)))
                                                      : VectorXd(VectorXd::Zero(m));
  SolveResult result;
  Timings timings;
  int iterations = 0, steps = 0;
  double change = 0;
  bool settled = false;
  while (steps < kMaxFixedPointSteps) {
    result = tresca(radii, step_options);
    ++steps;
    iterations += result.iterations;
    timings.merge(result.timings);
    if (result.status != Status::Converged) break;
    const VectorXd next = mu.cwiseProduct(result.lambda.cwiseMax(0.0));
    change = relative(inf_norm(VectorXd(next - radii)), inf_norm(next));
    radii = next;
    if (change <= options.tol) {
      settled = true;
      break;
    }
    // The next step starts from this one's answer and reuses its solver of K.
    step_options.initial = InitialGuess{result.u, result.lambda, result.lambda_t};
    if (result.K_factor) step_options.K_factor = result.K_factor;
  }
  result.iterations = iterations;
  result.timings = timings;
  result.diagnostics["fixed_point_steps"] = steps;
  result.diagnostics["fixed_point_change"] = change;
  const std::string counts = std::to_string(steps) + " Tresca solves, " + std::to_string(iterations) +
                             " iterations in all; last relative change of μλ_N " + short_number(change);
  if (result.status != Status::Converged) {
    result.message = "Coulomb's fixed point stopped at Tresca solve " + std::to_string(steps) + " (" + counts +
                     "): " + result.message;
  } else if (!settled) {
    result.status = Status::MaxIterations;
    result.message = "Coulomb's fixed point did not settle in " + std::to_string(steps) + " Tresca solves (" + counts +
                     ", tol " + short_number(options.tol) + "); a smaller μ converges faster";
  } else {
    result.message = "converged: Coulomb's fixed point (" + counts + "); last solve " + result.message;
  }
  return result;
}

}  // namespace contactqp::detail
