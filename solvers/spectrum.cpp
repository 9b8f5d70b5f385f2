#include "spectrum.hpp"
#include "qp/dense_decompositions.hpp"

#include <algorithm>
#include <cmath>

namespace contactqp::detail {
namespace {

// The rows `rows` of B, in that order.
SparseMatrix select_rows(const SparseMatrix& B, const std::vector<int>& rows) {
  std::vector<int> position(B.rows(), -1);
  for (int i = 0; i < static_cast<int>(rows.size()); ++i) position[rows[i]] = i;
  std::vector<Eigen::Triplet<double>> entries;
  for (int column = 0; column < B.outerSize(); ++column)
    for (SparseMatrix::InnerIterator it(B, column); it; ++it)
      if (position[it.row()] >= 0) entries.emplace_back(position[it.row()], column, it.value());
  SparseMatrix selected(static_cast<int>(rows.size()), B.cols());
  selected.setFromTriplets(entries.begin(), entries.end());
  return selected;
}

// Ritz values over this many steps must have settled before the estimate is accepted: the
// extreme Ritz values of Lanczos move monotonically, and a short pause is not convergence.
constexpr int kSettleWindow = 5;

}  // namespace

SpectrumEstimate estimate_spectrum(const QuadraticProgram& qp, const LinearSolver& K_factor,
                                   const std::vector<int>& rows, int max_steps, double rel_tol_max,
                                   double rel_tol_min) {
  return estimate_spectrum(qp.B, K_factor, rows, max_steps, rel_tol_max, rel_tol_min);
}

SpectrumEstimate estimate_spectrum(const SparseMatrix& B, const LinearSolver& K_factor, const std::vector<int>& rows,
                                   int max_steps, double rel_tol_max, double rel_tol_min) {
  SpectrumEstimate estimate;
  Stopwatch clock;
  const SparseMatrix B_R = rows.empty() ? B : select_rows(B, rows);
  const SparseMatrix B_R_transposed = B_R.transpose();
  const int r = static_cast<int>(B_R.rows());
  estimate.rows = r;
  if (r == 0) return estimate;

  // A start vector with a component along every eigenvector in practice: all ones plus a
  // deterministic ripple, so that results are reproducible run to run.
  VectorXd q(r);
  for (int i = 0; i < r; ++i) q[i] = 1.0 + 0.5 * std::sin(1.0 + 7.0 * i);
  q.normalize();

  const int n_steps = std::min(r, max_steps);
  Eigen::MatrixXd Q(r, n_steps);
  VectorXd alpha(n_steps), beta(n_steps);
  std::vector<double> theta_min, theta_max;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ritz;
  for (int j = 0; j < n_steps; ++j) {
    Q.col(j) = q;
    VectorXd w = B_R * K_factor.solve(VectorXd(B_R_transposed * q));
    ++estimate.applications;
    alpha[j] = q.dot(w);
    // Full reorthogonalisation (classical Gram–Schmidt, twice): without it, converged Ritz
    // values reappear as spurious copies; with m at most a few thousand it costs little next
    // to the solve. It also subtracts the three-term recurrence α_j q_j + β_{j−1} q_{j−1}.
    for (int pass = 0; pass < 2; ++pass) w -= Q.leftCols(j + 1) * (Q.leftCols(j + 1).transpose() * w);
    beta[j] = w.norm();

    ritz.computeFromTridiagonal(alpha.head(j + 1), beta.head(j), Eigen::EigenvaluesOnly);
    theta_min.push_back(ritz.eigenvalues()[0]);
    theta_max.push_back(ritz.eigenvalues()[j]);
    estimate.lambda_min = std::max(0.0, theta_min.back());
    estimate.lambda_max = theta_max.back();

    // An invariant Krylov space (always reached at step |R|): the Ritz values are eigenvalues.
    if (!(beta[j] > 1e-12 * std::max(std::abs(theta_max.back()), 1e-300))) {
      estimate.converged = true;
      break;
    }
    if (j >= kSettleWindow) {
      const double change_max = std::abs(theta_max[j] - theta_max[j - kSettleWindow]);
      const double change_min = std::abs(theta_min[j] - theta_min[j - kSettleWindow]);
      const double floor_min = 1e-12 * std::abs(theta_max[j]);
      if (change_max <= rel_tol_max * std::abs(theta_max[j]) &&
          change_min <= rel_tol_min * std::max(std::abs(theta_min[j]), floor_min)) {
        estimate.converged = true;
        break;
      }
    }
    q = w / beta[j];
  }
  estimate.seconds = clock.seconds();
  return estimate;
}

SpectrumEstimate estimate_lambda_max(const QuadraticProgram& qp, const LinearSolver& K_factor) {
  return estimate_spectrum(qp, K_factor);
}

}  // namespace contactqp::detail
