// Evidence of a QP without solution (no_solution.hpp).
#include "no_solution.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "contactqp/cholesky.hpp"
#include "nnls.hpp"
#include "qp/dense_decompositions.hpp"

namespace contactqp::detail {
namespace {

// Dense eigenvalues below this size: exact and cheaper than a factorisation's set-up.
constexpr int kDenseEigenMaxSize = 600;

Eigen::MatrixXd orthonormal(const Eigen::MatrixXd& X) {
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(X);
  return qr.householderQ() * Eigen::MatrixXd::Identity(X.rows(), X.cols());
}

// The columns of V whose eigenvalue of H (the Rayleigh quotient matrix) is at most threshold.
Eigen::MatrixXd small_eigenvectors(const Eigen::MatrixXd& H, const Eigen::MatrixXd& V, double threshold) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(H);
  std::vector<int> kept;
  for (int j = 0; j < H.rows(); ++j)
    if (eigen.eigenvalues()(j) <= threshold) kept.push_back(j);
  Eigen::MatrixXd N(V.rows(), static_cast<long>(kept.size()));
  for (size_t c = 0; c < kept.size(); ++c) N.col(static_cast<long>(c)) = V * eigen.eigenvectors().col(kept[c]);
  return N;
}

}  // namespace

double longest_carried_length(const QuadraticProgram& qp) {
  const double stiffness = infinity_norm(qp.K);
  if (!(stiffness > 0)) return std::numeric_limits<double>::infinity();
  const double push = qp.g.size() ? stiffness * qp.g.cwiseAbs().maxCoeff() : 0.0;
  const double load = std::max(qp.f.size() ? qp.f.cwiseAbs().maxCoeff() : 0.0, push);
  return load / (kNullRelative * stiffness);
}

Eigen::MatrixXd null_space_of(const SparseMatrix& K) {
  const int n = static_cast<int>(K.rows());
  const double norm = infinity_norm(K);
  if (norm == 0) return Eigen::MatrixXd::Identity(n, n);
  const double threshold = kNullRelative * norm;
  if (n <= kDenseEigenMaxSize) {
    const Eigen::MatrixXd dense = Eigen::MatrixXd(K);
    const Eigen::MatrixXd symmetric = 0.5 * (dense + dense.transpose());
    return small_eigenvectors(symmetric, Eigen::MatrixXd::Identity(n, n), threshold);
  }
  // Inverse iteration amplifies an eigenvector by 1/(λ + σ): with σ = 1e-9 ‖K‖ the null space
  // grows 1e3 times faster per step than an eigenvalue of 1e-6 ‖K‖, far below an elastic
  // body's smallest (about h² of the largest). Blocks of 12 hold the 6 rigid modes of two 3D
  // bodies; a block whose every Ritz value is null is doubled.
  SparseMatrix shifted = K;
  for (int i = 0; i < n; ++i) shifted.coeffRef(i, i) += 1e-9 * norm;
  const CholeskyFactor factor(shifted, Ordering::Amd);
  if (!factor.ok()) return Eigen::MatrixXd(n, 0);
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  for (int block = 12;; block *= 2) {
    block = std::min(block, n);
    Eigen::MatrixXd X = Eigen::MatrixXd::NullaryExpr(n, block, [&]() { return normal(random); });
    for (int step = 0; step < 4; ++step) X = orthonormal(factor.solve_columns(X));
    const Eigen::MatrixXd KX = K * X;
    const Eigen::MatrixXd H = 0.5 * (X.transpose() * KX + KX.transpose() * X);
    Eigen::MatrixXd N = small_eigenvectors(H, X, threshold);
    if (N.cols() < block || block == n) return N.cols() == 0 ? N : orthonormal(N);
  }
}

VectorXd recession_direction(const QuadraticProgram& qp, const Eigen::MatrixXd& R) {
  if (R.cols() == 0 || !qp.friction.empty()) return {};
  const Eigen::VectorXd free_load = R.transpose() * qp.f;  // the load on each free mode
  const double load = qp.f.norm();
  if (free_load.norm() <= 1e-12 * load) return {};  // nothing drives the free modes
  // Columns: the free-mode components of each row's force, Rᵀ Bᵀ e_i.
  const SparseMatrix A = (qp.B * R).transpose().sparseView();
  const NnlsResult fit = nnls(A, free_load, 1e-14, 10 * static_cast<int>(R.cols()) + 10);
  const Eigen::VectorXd w = fit.residual;  // the load no row balances
  if (w.norm() <= 1e-9 * load) return {};
  VectorXd d = R * w;
  d /= d.norm();
  // Check the evidence in the caller's terms (rows of B have unit norm): it must be what it claims.
  const double along = qp.f.dot(d);
  const double rise = qp.n_constraints() == 0 ? 0.0 : (qp.B * d).maxCoeff();
  if (!(along > 0) || rise > 1e-9) return {};
  return d;
}

VectorXd farkas_direction(const QuadraticProgram& qp, double tol) {
  const int m = qp.n_constraints();
  const int n = qp.n_dofs();
  if (m == 0 || m > kFarkasMaxRows || qp.g.minCoeff() >= 0) return {};
  const double gap_scale = qp.g.cwiseAbs().maxCoeff();
  // A = [Bᵀ; gᵀ/‖g‖∞], b = (0, ..., 0, −1).
  std::vector<Eigen::Triplet<double>> entries;
  for (int j = 0; j < qp.B.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(qp.B, j); it; ++it) entries.emplace_back(it.col(), it.row(), it.value());
  for (int i = 0; i < m; ++i) entries.emplace_back(n, i, qp.g(i) / gap_scale);
  SparseMatrix A(n + 1, m);
  A.setFromTriplets(entries.begin(), entries.end());
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n + 1);
  b(n) = -1;
  // Rows that contradict each other are few; a search that needs more steps finds no evidence.
  const NnlsResult fit = nnls(A, b, 1e-14, kFarkasMaxSteps);
  if (fit.x.maxCoeff() <= 0) return {};
  const VectorXd y = fit.x / fit.x.maxCoeff();
  const double gy = qp.g.dot(y);
  const double unbalanced = (qp.B.transpose() * y).cwiseAbs().maxCoeff();
  // Any feasible u has ‖u‖₁ ≥ −gᵀy / ‖Bᵀy‖∞ (since yᵀB u ≤ yᵀg): beyond ‖g‖∞/tol, no answer
  // at the requested accuracy exists.
  if (!(gy < 0) || -gy * tol <= unbalanced * gap_scale) return {};
  return y;
}

}  // namespace contactqp::detail
