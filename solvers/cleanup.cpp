// What solve() does to every backend's result after the backend returns: exact zeros for the
// multipliers of rows that clearly separate, and no overflowed iterate.
//
// Why zero multipliers: an interior point keeps λ_i·s_i ≈ μ > 0 on every row (s_i = g_i −
// (Bu)_i the slack), so rows that separate come back with λ_i = μ/s_i — tiny but not 0 —
// while the projection methods (uzawa, nlopt) land on 0 exactly. A node that does not touch
// carries no force: where the answer is "no contact", every backend should say λ = 0. The
// rule is the same for every backend (a no-op for the projection methods):
//   zero λ_i when s_i > √tol · L   (clearly positive: beyond the √tol band in which a
//                                    degenerate active row may sit, docs/architecture.md's Hölder bound)
// row by row, smallest λ_i first, as long as the certificate's stationarity residual — the one
// residual it can worsen — stays within max(tol, its value before) relative to the force
// scale; complementarity and the duality gap only improve, primal feasibility does not
// change. A row whose multiplier is too large to drop keeps it. So the result is certified as
// before, and a caller's certify() sees the zeros.
#include <algorithm>
#include <cmath>
#include <vector>

#include "backends.hpp"
#include "cleanup.hpp"
#include "contactqp/certificate.hpp"
#include "qp/norms.hpp"

namespace contactqp::detail {
namespace {

using RowMajorMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

}  // namespace

void zero_separated_multipliers(const QuadraticProgram& qp, const KTimes& K_times, SolveResult& result, double tol) {
  if (result.status != Status::Converged || result.lambda.size() == 0) return;
  const VectorXd& u = result.u;
  VectorXd& lambda = result.lambda;
  const VectorXd slack = qp.g - qp.B * u;
  const double threshold = std::sqrt(tol) * length_scale(qp, u);
  std::vector<int> rows;
  for (int i = 0; i < lambda.size(); ++i)
    if (lambda[i] != 0.0 && slack[i] > threshold) rows.push_back(i);
  if (rows.empty()) return;

  // The stationarity residual r = Ku − f + Bᵀλ, and the bound each of its entries must keep:
  // the relative residual it had, or tol, measured by the part of the force scale that the
  // zeros cannot lower (‖f‖∞, ‖Ku‖∞).
  const VectorXd Ku = K_times(u);
  const VectorXd Btl = qp.B.transpose() * lambda;
  VectorXd r = Ku - qp.f + Btl;
  const double fixed_force = std::max(inf_norm(qp.f), inf_norm(Ku));
  const double force = std::max(fixed_force, inf_norm(Btl));
  const double bound = std::max(tol * fixed_force, force > 0 ? inf_norm(r) * fixed_force / force : 0.0);
  const RowMajorMatrix B = qp.B;
  std::sort(rows.begin(), rows.end(), [&](int a, int b) { return lambda[a] < lambda[b]; });
  int zeroed = 0;
  for (int i : rows) {
    bool within = true;
    for (RowMajorMatrix::InnerIterator it(B, i); it && within; ++it)
      within = std::abs(r[it.col()] - lambda[i] * it.value()) <= bound;
    if (!within) continue;
    for (RowMajorMatrix::InnerIterator it(B, i); it; ++it) r[it.col()] -= lambda[i] * it.value();
    lambda[i] = 0.0;
    ++zeroed;
  }
  if (zeroed > 0) result.diagnostics["zeroed_multipliers"] = zeroed;
}

bool overflows(const QuadraticProgram& qp, const KTimes& K_times, const SolveResult& result) {
  // Finite u and λ can still be too large to certify (a diverged iteration stopped at 1e298):
  // the energy, Bᵀλ and the complementarity products must be finite too.
  if (!std::isfinite(0.5 * result.u.dot(K_times(result.u)) - qp.f.dot(result.u))) return true;
  if (!VectorXd(qp.B.transpose() * result.lambda).allFinite()) return true;
  const VectorXd products = result.lambda.cwiseProduct(VectorXd(qp.B * result.u - qp.g));
  return !products.allFinite() || !std::isfinite(result.lambda.dot(qp.g));
}

}  // namespace contactqp::detail
