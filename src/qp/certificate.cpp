#include "contactqp/certificate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "contactqp/cholesky.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/number_format.hpp"
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

double force_scale(const VectorXd& f, const VectorXd& Ku, const VectorXd& Btl) {
  return std::max({inf_norm(f), inf_norm(Ku), inf_norm(Btl)});
}

double force_scale(const QuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda, const VectorXd& lambda_t) {
  const double F = force_scale(qp.f, K_times(qp, u), qp.B.transpose() * lambda);
  if (qp.friction.empty() || lambda_t.size() == 0) return F;
  return std::max(F, inf_norm(VectorXd(qp.friction.T.transpose() * lambda_t)));
}

double length_scale(const QuadraticProgram& qp, const VectorXd& u) {
  const VectorXd Bu = qp.B * u;
  return std::max(inf_norm(u), inf_norm(Bu));
}

double Certificate::kkt_max() const {
  return std::max({stationarity, primal_feasibility, dual_feasibility, complementarity, tangential});
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
  return certify(qp, u, lambda, VectorXd(), K_factor);  // with friction, λ_T read as 0
}

// With friction the formulas gain T's rows (certificate.hpp); without, certificate_terms().
Certificate certify(const QuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda, const VectorXd& lambda_t,
                    const LinearSolver* K_factor) {
  std::unique_ptr<CholeskyFactor> own_factor;
  if (!K_factor) {
    own_factor = std::make_unique<CholeskyFactor>(qp.K);
    K_factor = own_factor.get();
  }
  return certify_given_Ku(qp, K_times(qp, u), u, lambda, lambda_t, K_factor);
}

Certificate certify_given_Ku(const QuadraticProgram& qp, const VectorXd& Ku, const VectorXd& u, const VectorXd& lambda,
                             const VectorXd& lambda_t_in, const LinearSolver* K_factor) {
  if (qp.friction.empty()) {
    CertificateTerms terms = certificate_terms(qp, Ku, u, lambda);
    if (K_factor && K_factor->ok()) {
      const VectorXd r = Ku - qp.f + qp.B.transpose() * lambda;
      terms.r_K_inverse_r = r.dot(K_factor->solve(r));
    }
    return certificate_from(terms);
  }
  Certificate c;
  const VectorXd lambda_t = tangential_multipliers(qp, lambda_t_in);
  const VectorXd Btl = qp.B.transpose() * lambda;
  const VectorXd Ttl = qp.friction.T.transpose() * lambda_t;
  VectorXd r = Ku - qp.f + Btl + Ttl;      // stationarity residual
  const VectorXd slack = qp.B * u - qp.g;  // ≤ 0 when feasible

  const double F = std::max(force_scale(qp.f, Ku, Btl), inf_norm(Ttl));
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
  const VectorXd slip = detail::slip_of(qp.friction, u);
  const VectorXd radii = detail::disc_radii(qp.friction, lambda);
  const double rho = F > 0 && L > 0 ? F / L : 1.0;
  c.tangential = relative(detail::natural_map_residual(qp.friction, lambda_t, radii, slip, rho), F);
  const double friction_energy = detail::dissipation(qp.friction, radii, slip);  // Σ r_i ‖slip_i‖
  lagrangian += lambda_t.dot(slip);
  c.objective += friction_energy;

  // θ(λ) = L(u, λ) − ½ rᵀK⁻¹r: exact, and accurate near the optimum where r → 0.
  c.dual_available = false;
  if (K_factor && K_factor->ok()) {
    c.dual_objective = lagrangian - 0.5 * r.dot(K_factor->solve(r));
    c.duality_gap = c.objective - c.dual_objective;
    const double energy = std::max({std::abs(c.objective), std::abs(c.dual_objective), 0.5 * std::abs(uKu),
                                    std::abs(qp.f.dot(u)), friction_energy});
    c.relative_gap = relative(c.duality_gap, energy);
    c.dual_available = std::isfinite(c.dual_objective);
  }
  if (!c.dual_available) c.dual_objective = c.duality_gap = c.relative_gap = 0;
  return c;
}

}  // namespace contactqp

namespace contactqp {

bool meets_tolerance(const Certificate& certificate, double tol) {
  const double bound = kCertifiedFactor * tol;
  if (!(certificate.kkt_max() <= bound)) return false;  // NaN fails too
  return !certificate.dual_available || std::abs(certificate.relative_gap) <= bound;
}

Status certified_status(const Certificate& certificate, double tol, Status proposed) {
  if (proposed == Status::Converged && !meets_tolerance(certificate, tol)) return Status::Inaccurate;
  return proposed;
}

void apply_certificate(SolveResult& result, const Certificate& certificate, double tol) {
  result.certificate = certificate;
  const Status proposed = result.status;
  result.status = certified_status(certificate, tol, proposed);
  if (result.status == proposed) return;
  result.message = "the backend stopped on its own test (" + result.message +
                   "), but its answer's certificate shows relative KKT residual " +
                   short_number(certificate.kkt_max()) +
                   (certificate.dual_available ? ", relative gap " + short_number(std::abs(certificate.relative_gap))
                                               : std::string()) +
                   ", above " + short_number(kCertifiedFactor) + " × tol = " + short_number(kCertifiedFactor * tol);
}

}  // namespace contactqp
