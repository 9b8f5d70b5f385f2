// What solve() does to every backend's result after the backend returns: exact zeros for the
// multipliers of rows that clearly separate, and no overflowed iterate.
//
// Why zero multipliers: an interior point keeps λ_i·s_i ≈ μ > 0 on every row (s_i = g_i −
// (Bu)_i the slack), so rows that separate come back with λ_i = μ/s_i — tiny but not 0 —
// while the projection methods (uzawa, nlopt) land on 0 exactly. A node that does not touch
// carries no force: where the answer is "no contact", every backend should say λ = 0. The
// rule is the same for every backend (a no-op for the projection methods):
//   zero λ_i when s_i > √tol · L   (clearly positive: beyond the √tol band in which a
//                                    degenerate active row may sit, ARCHITECTURE.md's Hölder bound)
// and keep the change only if the certificate's relative stationarity residual, the one
// residual it can worsen, stays within max(tol, its value before) — complementarity and the
// duality gap only improve, primal feasibility does not change. So the result is certified
// as before, and a caller's certify() sees the zeros.
#include <cmath>

#include "backends.hpp"
#include "contactqp/certificate.hpp"

namespace contactqp::detail {
namespace {

double inf_norm_of(const VectorXd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

double relative_stationarity(const QuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda) {
  const double F = force_scale(qp, u, lambda);
  const double r = inf_norm_of(VectorXd(qp.K * u - qp.f + qp.B.transpose() * lambda));
  return F > 0 ? r / F : r;
}

}  // namespace

void zero_separated_multipliers(const QuadraticProgram& qp, SolveResult& result, double tol) {
  if (result.status != Status::Converged || result.lambda.size() == 0) return;
  const VectorXd slack = qp.g - qp.B * result.u;
  const double threshold = std::sqrt(tol) * length_scale(qp, result.u);
  VectorXd cleaned = result.lambda;
  int zeroed = 0;
  for (int i = 0; i < cleaned.size(); ++i)
    if (cleaned[i] != 0.0 && slack[i] > threshold) {
      cleaned[i] = 0.0;
      ++zeroed;
    }
  if (zeroed == 0) return;
  const double before = relative_stationarity(qp, result.u, result.lambda);
  const double after = relative_stationarity(qp, result.u, cleaned);
  if (!(after <= std::max(tol, before))) return;  // the multipliers were not negligible: keep them
  result.lambda = cleaned;
  result.diagnostics["zeroed_multipliers"] = zeroed;
}

bool overflows(const QuadraticProgram& qp, const SolveResult& result) {
  // Finite u and λ can still be too large to certify (a diverged iteration stopped at 1e298):
  // the energy, Bᵀλ and the complementarity products must be finite too.
  if (!std::isfinite(primal_objective(qp, result.u))) return true;
  if (!VectorXd(qp.B.transpose() * result.lambda).allFinite()) return true;
  const VectorXd products = result.lambda.cwiseProduct(VectorXd(qp.B * result.u - qp.g));
  return !products.allFinite() || !std::isfinite(result.lambda.dot(qp.g));
}

}  // namespace contactqp::detail
