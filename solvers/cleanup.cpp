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

  // The stationarity residual r = Ku − f + Bᵀλ (+ Tᵀλ_T), and the bound each of its entries must
  // keep: the relative residual it had, or tol, measured by the part of the force scale that the
  // zeros cannot lower (‖f‖∞, ‖Ku‖∞).
  const bool friction = !qp.friction.empty() && result.lambda_t.size() == qp.friction.T.rows();
  const VectorXd Ku = K_times(u);
  const VectorXd Btl = qp.B.transpose() * lambda;
  VectorXd r = Ku - qp.f + Btl;
  if (friction) r += qp.friction.T.transpose() * result.lambda_t;
  const double fixed_force = std::max(inf_norm(qp.f), inf_norm(Ku));
  const double force = std::max(fixed_force, inf_norm(Btl));
  const double bound = std::max(tol * fixed_force, force > 0 ? inf_norm(r) * fixed_force / force : 0.0);
  const RowMajorMatrix B = qp.B;
  // Under Coulomb's law a row's λ_T lies in the disc of radius μλ_N: it goes to zero with λ_N.
  const bool with_tangential = friction && qp.friction.law == FrictionLaw::Coulomb;
  const RowMajorMatrix T = with_tangential ? RowMajorMatrix(qp.friction.T) : RowMajorMatrix();
  const int nd = qp.friction.n_directions;
  // The change of r when row i's multipliers go to zero, one (entry, change) pair per entry of r.
  auto change_of = [&](int i) {
    std::vector<std::pair<int, double>> change;
    auto add = [&change](int entry, double value) {
      for (auto& [known, sum] : change)
        if (known == entry) {
          sum += value;
          return;
        }
      change.emplace_back(entry, value);
    };
    for (RowMajorMatrix::InnerIterator it(B, i); it; ++it) add(static_cast<int>(it.col()), -lambda[i] * it.value());
    if (with_tangential)
      for (int k = 0; k < nd; ++k)
        for (RowMajorMatrix::InnerIterator it(T, i * nd + k); it; ++it)
          add(static_cast<int>(it.col()), -result.lambda_t[i * nd + k] * it.value());
    return change;
  };
  std::sort(rows.begin(), rows.end(), [&](int a, int b) { return lambda[a] < lambda[b]; });
  int zeroed = 0;
  for (int i : rows) {
    const std::vector<std::pair<int, double>> change = change_of(i);
    bool within = true;
    for (size_t k = 0; k < change.size() && within; ++k)
      within = std::abs(r[change[k].first] + change[k].second) <= bound;
    if (!within) continue;
    for (const auto& [entry, value] : change) r[entry] += value;
    lambda[i] = 0.0;
    if (with_tangential) result.lambda_t.segment(i * nd, nd).setZero();
    ++zeroed;
  }
  if (zeroed > 0) result.diagnostics["zeroed_multipliers"] = zeroed;
}

bool overflows(const QuadraticProgram& qp, const KTimes& K_times, const SolveResult& result) {
  // Finite u and λ can still be too large to certify (a diverged iteration stopped at 1e298):
  // the energy, Bᵀλ and the complementarity products must be finite too.
  if (!std::isfinite(0.5 * result.u.dot(K_times(result.u)) - qp.f.dot(result.u))) return true;
  if (!VectorXd(qp.B.transpose() * result.lambda).allFinite()) return true;
  if (!qp.friction.empty() && result.lambda_t.size() == qp.friction.T.rows() &&
      (!VectorXd(qp.friction.T.transpose() * result.lambda_t).allFinite() ||
       !std::isfinite(result.lambda_t.dot(qp.friction.offset))))
    return true;
  const VectorXd products = result.lambda.cwiseProduct(VectorXd(qp.B * result.u - qp.g));
  return !products.allFinite() || !std::isfinite(result.lambda.dot(qp.g));
}

}  // namespace contactqp::detail
