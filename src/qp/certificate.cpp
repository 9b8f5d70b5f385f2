#include "contactqp/certificate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contactqp/cholesky.hpp"
#include "contactqp/errors.hpp"
#include "norms.hpp"
#include "qp/friction_sets.hpp"

namespace contactqp {
namespace {

// λ_T as the certificate reads it: zeros when the caller passed none.
VectorXd tangential_multipliers(const QuadraticProgram& qp, const VectorXd& lambda_t) {
  const long rows = qp.friction.T.rows();
  if (lambda_t.size() == 0) return VectorXd::Zero(rows);
  if (lambda_t.size() != rows)
    throw InputError("lambda_t",
                     "has " + std::to_string(lambda_t.size()) + " entries, T has " + std::to_string(rows) + " rows");
  return lambda_t;
}

}  // namespace

double force_scale(const QuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda, const VectorXd& lambda_t) {
  const VectorXd Ku = K_times(qp, u);
  const VectorXd Btl = qp.B.transpose() * lambda;
  const double F = std::max({inf_norm(qp.f), inf_norm(Ku), inf_norm(Btl)});
  if (qp.friction.empty() || lambda_t.size() == 0) return F;
  return std::max(F, inf_norm(VectorXd(qp.friction.T.transpose() * lambda_t)));
}

double length_scale(const QuadraticProgram& qp, const VectorXd& u) {
  const VectorXd Bu = qp.B * u;
  const double L = std::max(inf_norm(u), inf_norm(Bu));
  if (qp.friction.empty()) return L;
  return std::max(L, inf_norm(detail::slip_of(qp.friction, u)));
}

double Certificate::kkt_max() const {
  return std::max({stationarity, primal_feasibility, dual_feasibility, complementarity, tangential});
}

Certificate certify(const QuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda,
                    const LinearSolver* K_factor) {
  return certify(qp, u, lambda, VectorXd(), K_factor);
}

Certificate certify(const QuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda, const VectorXd& lambda_t_in,
                    const LinearSolver* K_factor) {
  Certificate c;
  const bool friction = !qp.friction.empty();
  const VectorXd lambda_t = friction ? tangential_multipliers(qp, lambda_t_in) : VectorXd();
  const VectorXd Ku = K_times(qp, u);
  const VectorXd Btl = qp.B.transpose() * lambda;
  VectorXd r = Ku - qp.f + Btl;            // stationarity residual
  const VectorXd slack = qp.B * u - qp.g;  // ≤ 0 when feasible
  if (friction) r += qp.friction.T.transpose() * lambda_t;

  const double F = force_scale(qp, u, lambda, lambda_t);
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
  double lagrangian = c.objective + lambda.dot(slack);
  double friction_energy = 0;  // Σ r_i ‖slip_i‖
  if (friction) {
    const VectorXd slip = detail::slip_of(qp.friction, u);
    const VectorXd radii = detail::disc_radii(qp.friction, lambda);
    const double rho = F > 0 && L > 0 ? F / L : 1.0;
    c.tangential = relative(detail::natural_map_residual(qp.friction, lambda_t, radii, slip, rho), F);
    friction_energy = detail::dissipation(qp.friction, radii, slip);
    lagrangian += lambda_t.dot(slip);
    c.objective += friction_energy;
  }

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
    double energy =
        std::max({std::abs(c.objective), std::abs(c.dual_objective), 0.5 * std::abs(uKu), std::abs(qp.f.dot(u))});
    if (friction) energy = std::max(energy, friction_energy);
    c.relative_gap = relative(c.duality_gap, energy);
    if (!std::isfinite(c.dual_objective)) c.dual_available = false;
  } else {
    c.dual_available = false;
  }
  if (!c.dual_available) c.dual_objective = c.duality_gap = c.relative_gap = 0;
  return c;
}

}  // namespace contactqp
