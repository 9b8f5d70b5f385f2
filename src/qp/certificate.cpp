#include "contactqp/certificate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contactqp/cholesky.hpp"
#include "norms.hpp"

namespace contactqp {
double force_scale(const QuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda) {
  const VectorXd Ku = K_times(qp, u);
  const VectorXd Btl = qp.B.transpose() * lambda;
  return std::max({inf_norm(qp.f), inf_norm(Ku), inf_norm(Btl)});
}

double length_scale(const QuadraticProgram& qp, const VectorXd& u) {
  const VectorXd Bu = qp.B * u;
  return std::max(inf_norm(u), inf_norm(Bu));
}

double Certificate::kkt_max() const {
  return std::max({stationarity, primal_feasibility, dual_feasibility, complementarity});
}

Certificate certify(const QuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda,
                    const LinearSolver* K_factor) {
  Certificate c;
  const VectorXd Ku = K_times(qp, u);
  const VectorXd Btl = qp.B.transpose() * lambda;
  const VectorXd r = Ku - qp.f + Btl;      // stationarity residual
  const VectorXd slack = qp.B * u - qp.g;  // ≤ 0 when feasible

  const double F = force_scale(qp, u, lambda);
  const double L = length_scale(qp, u);
  const double lambda_max = inf_norm(lambda);

  c.stationarity = relative(inf_norm(r), F);
  c.primal_feasibility = relative(slack.size() ? std::max(0.0, slack.maxCoeff()) : 0.0, L);
  c.dual_feasibility = relative(lambda.size() ? std::max(0.0, -lambda.minCoeff()) : 0.0, std::max(lambda_max, F));
  double complementarity = 0;
  for (int i = 0; i < slack.size(); ++i) complementarity = std::max(complementarity, std::abs(lambda[i] * slack[i]));
  c.complementarity = relative(complementarity, std::max(lambda_max, F) * L);

  const double uKu = u.dot(Ku);
  c.objective = 0.5 * uKu - qp.f.dot(u);
  const double lagrangian = c.objective + lambda.dot(slack);

  // θ(λ) = L(u, λ) − ½ rᵀK⁻¹r: exact, and accurate near the optimum where r → 0.
  std::unique_ptr<CholeskyFactor> own_factor;
  if (!K_factor && qp.K_is_rank_share) {
    c.dual_available = false;  // no rank holds K to factorise; the backend passes its solver of K
  } else if (!K_factor) {
    own_factor = std::make_unique<CholeskyFactor>(qp.K);
    K_factor = own_factor.get();
  }
  if (K_factor && K_factor->ok()) {
    const VectorXd Kinv_r = K_factor->solve(r);
    c.dual_objective = lagrangian - 0.5 * r.dot(Kinv_r);
    c.duality_gap = c.objective - c.dual_objective;
    const double energy =
        std::max({std::abs(c.objective), std::abs(c.dual_objective), 0.5 * std::abs(uKu), std::abs(qp.f.dot(u))});
    c.relative_gap = relative(c.duality_gap, energy);
    if (!std::isfinite(c.dual_objective)) c.dual_available = false;
  } else {
    c.dual_available = false;
  }
  if (!c.dual_available) c.dual_objective = c.duality_gap = c.relative_gap = 0;
  return c;
}

}  // namespace contactqp
