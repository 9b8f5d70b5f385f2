#include "scaling.hpp"

#include <cmath>

#include "contactqp/backends/uzawa.hpp"
#include "contactqp/linear_solver.hpp"
#include "qp/norms.hpp"

namespace contactqp::detail {
namespace {

// Diagnostics that carry units: steps ρ scale like κ, eigenvalues of S = B K⁻¹ Bᵀ like 1/κ.
const char* const kStepDiagnostics[] = {"rho", "rho_max", "rho_opt"};
const char* const kEigenvalueDiagnostics[] = {"lambda_max_S", "lambda_min_S"};

}  // namespace

QpScaling choose_scaling(const QuadraticProgram& qp, const VectorXd& diagonal) {
  QpScaling scaling;
  const double kappa = diagonal.size() ? diagonal.cwiseAbs().maxCoeff() : 0.0;
  if (kappa > 0 && std::isfinite(kappa)) scaling.stiffness = kappa;
  const double from_load = inf_norm(qp.f) / scaling.stiffness;
  const double from_gap = inf_norm(qp.g);
  if (from_load > 0 && std::isfinite(from_load))
    scaling.displacement = from_load;
  else if (from_gap > 0 && std::isfinite(from_gap))
    scaling.displacement = from_gap;
  return scaling;
}

QuadraticProgram scaled_qp(const QuadraticProgram& qp, const QpScaling& scaling) {
  QuadraticProgram scaled;
  scaled.K = qp.K / scaling.stiffness;
  scaled.f = qp.f / (scaling.stiffness * scaling.displacement);
  scaled.B = qp.B;
  scaled.g = qp.g / scaling.displacement;
  scaled.rows = qp.rows;
  scaled.near_null_space = qp.near_null_space;  // directions: unchanged by the scaling of K
  scaled.null_space = qp.null_space;            // the same
  scaled.coarse_space = qp.coarse_space;        // an interpolation: unchanged too
  // T's rows are unit directions like B's; the offset is a length, the threshold a force, μ a ratio.
  scaled.friction = qp.friction;
  scaled.friction.offset = qp.friction.offset / scaling.displacement;
  scaled.friction.threshold = qp.friction.threshold / (scaling.stiffness * scaling.displacement);
  return scaled;
}

SolveOptions scaled_options(const SolveOptions& options, const QpScaling& scaling) {
  SolveOptions scaled = options;
  UzawaOptions uzawa = options.get<UzawaOptions>();
  if (uzawa.rho_rule == UzawaOptions::RhoRule::Absolute) uzawa.rho /= scaling.stiffness;
  uzawa.rho_unit *= scaling.stiffness;
  scaled.set(uzawa);
  if (options.K_factor) scaled.K_factor = options.K_factor->scaled(1.0 / scaling.stiffness);
  const double force = scaling.stiffness * scaling.displacement;
  scaled.initial.u = options.initial.u / scaling.displacement;
  scaled.initial.lambda = options.initial.lambda / force;
  scaled.initial.lambda_t = options.initial.lambda_t / force;
  if (options.observer) {
    // The observer sees iterates in the caller's units, like the final result.
    scaled.observer = [observer = options.observer, scaling](int k, const VectorXd& u, const VectorXd& lambda) {
      observer(k, u * scaling.displacement, lambda * (scaling.stiffness * scaling.displacement));
    };
  }
  return scaled;
}

void unscale_result(SolveResult& result, const QpScaling& scaling) {
  result.u *= scaling.displacement;
  result.lambda *= scaling.stiffness * scaling.displacement;
  result.lambda_t *= scaling.stiffness * scaling.displacement;
  for (const char* key : kStepDiagnostics) {
    auto it = result.diagnostics.find(key);
    if (it != result.diagnostics.end()) it->second *= scaling.stiffness;
  }
  for (const char* key : kEigenvalueDiagnostics) {
    auto it = result.diagnostics.find(key);
    if (it != result.diagnostics.end()) it->second /= scaling.stiffness;
  }
  if (result.K_factor) result.K_factor = result.K_factor->scaled(scaling.stiffness);
}

}  // namespace contactqp::detail
