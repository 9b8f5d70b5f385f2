#include "contactqp/certificate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contactqp/cholesky.hpp"
#include "norms.hpp"

namespace contactqp {

double force_scale(const VectorXd& f, const VectorXd& Ku, const VectorXd& Btl) {
  return std::max({inf_norm(f), inf_norm(Ku), inf_norm(Btl)});
}

double force_scale(const QuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda) {
  return force_scale(qp.f, K_times(qp, u), qp.B.transpose() * lambda);
}

double length_scale(const QuadraticProgram& qp, const VectorXd& u) {
  const VectorXd Bu = qp.B * u;
  return std::max(inf_norm(u), inf_norm(Bu));
}

double Certificate::kkt_max() const {
  return std::max({stationarity, primal_feasibility, dual_feasibility, complementarity});
}

CertificateTerms certificate_terms(const QuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda) {
  return certificate_terms(qp, K_times(qp, u), u, lambda);
}

CertificateTerms certificate_terms(const QuadraticProgram& qp, const VectorXd& Ku, const VectorXd& u,
                                   const VectorXd& lambda) {
  CertificateTerms t;
  const VectorXd Btl = qp.B.transpose() * lambda;
  const VectorXd r = Ku - qp.f + Btl;  // stationarity residual
  const VectorXd Bu = qp.B * u;
  const VectorXd slack = Bu - qp.g;  // ≤ 0 when feasible
  t.f_max = inf_norm(qp.f);
  t.Ku_max = inf_norm(Ku);
  t.Btl_max = inf_norm(Btl);
  t.u_max = inf_norm(u);
  t.Bu_max = inf_norm(Bu);
  t.stationarity_max = inf_norm(r);
  t.violation_max = slack.size() ? std::max(0.0, slack.maxCoeff()) : 0.0;
  t.negative_max = lambda.size() ? std::max(0.0, -lambda.minCoeff()) : 0.0;
  t.lambda_max = inf_norm(lambda);
  for (int i = 0; i < slack.size(); ++i)
    t.complementarity_max = std::max(t.complementarity_max, std::abs(lambda[i] * slack[i]));
  t.uKu = u.dot(Ku);
  t.fu = qp.f.dot(u);
  t.lambda_slack = lambda.dot(slack);
  return t;
}

Certificate certificate_from(const CertificateTerms& t) {
  Certificate c;
  const double F = std::max({t.f_max, t.Ku_max, t.Btl_max});
  const double L = std::max(t.u_max, t.Bu_max);
  c.stationarity = relative(t.stationarity_max, F);
  c.primal_feasibility = relative(t.violation_max, L);
  c.dual_feasibility = relative(t.negative_max, std::max(t.lambda_max, F));
  c.complementarity = relative(t.complementarity_max, std::max(t.lambda_max, F) * L);
  c.objective = 0.5 * t.uKu - t.fu;
  const double lagrangian = c.objective + t.lambda_slack;
  // θ(λ) = L(u, λ) − ½ rᵀK⁻¹r: exact, and accurate near the optimum where r → 0.
  c.dual_available = !std::isnan(t.r_K_inverse_r);
  if (c.dual_available) {
    c.dual_objective = lagrangian - 0.5 * t.r_K_inverse_r;
    c.duality_gap = c.objective - c.dual_objective;
    const double energy =
        std::max({std::abs(c.objective), std::abs(c.dual_objective), 0.5 * std::abs(t.uKu), std::abs(t.fu)});
    c.relative_gap = relative(c.duality_gap, energy);
    if (!std::isfinite(c.dual_objective)) c.dual_available = false;
  }
  if (!c.dual_available) c.dual_objective = c.duality_gap = c.relative_gap = 0;
  return c;
}

Certificate certify(const QuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda,
                    const LinearSolver* K_factor) {
  const VectorXd Ku = K_times(qp, u);
  CertificateTerms terms = certificate_terms(qp, Ku, u, lambda);
  std::unique_ptr<CholeskyFactor> own_factor;
  if (!K_factor) {
    own_factor = std::make_unique<CholeskyFactor>(qp.K);
    K_factor = own_factor.get();
  }
  if (K_factor->ok()) {
    const VectorXd r = Ku - qp.f + qp.B.transpose() * lambda;
    terms.r_K_inverse_r = r.dot(K_factor->solve(r));
  }
  return certificate_from(terms);
}

}  // namespace contactqp
