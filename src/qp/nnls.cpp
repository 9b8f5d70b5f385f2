// Lawson–Hanson NNLS (nnls.hpp).
#include "nnls.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <vector>

namespace contactqp::detail {
namespace {

// z minimising ‖A_P z − b‖ over the passive columns P (unconstrained), by the normal equations
// with a pivoted LDLᵀ: the passive columns are independent in exact arithmetic.
Eigen::VectorXd passive_solution(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b,
                                 const std::vector<int>& passive) {
  const int p = static_cast<int>(passive.size());
  std::vector<Eigen::Triplet<double>> entries;
  for (int c = 0; c < p; ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, passive[c]); it; ++it)
      entries.emplace_back(it.row(), c, it.value());
  Eigen::SparseMatrix<double> AP(A.rows(), p);
  AP.setFromTriplets(entries.begin(), entries.end());
  const Eigen::MatrixXd G = Eigen::MatrixXd(AP.transpose() * AP);
  const Eigen::VectorXd h = AP.transpose() * b;
  return G.ldlt().solve(h);
}

}  // namespace

NnlsResult nnls(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b, double tol, int max_steps) {
  const int m = static_cast<int>(A.cols());
  NnlsResult out;
  out.x = Eigen::VectorXd::Zero(m);
  out.residual = b;
  std::vector<bool> in_passive(m, false);
  std::vector<int> passive;
  const Eigen::VectorXd Atb = A.transpose() * b;
  const double threshold = tol * std::max(Atb.cwiseAbs().maxCoeff(), 1e-300);
  while (out.steps < max_steps) {
    // The column whose gradient −Aᵀ(Ax − b) is largest outside the passive set.
    const Eigen::VectorXd w = A.transpose() * out.residual;
    int best = -1;
    for (int j = 0; j < m; ++j)
      if (!in_passive[j] && w(j) > threshold && (best < 0 || w(j) > w(best))) best = j;
    if (best < 0) {
      out.converged = true;
      break;
    }
    ++out.steps;
    in_passive[best] = true;
    passive.push_back(best);
    for (int inner = 0; inner < 3 * m + 3; ++inner) {
      const Eigen::VectorXd z = passive_solution(A, b, passive);
      if (z.minCoeff() > 0) {
        for (size_t i = 0; i < passive.size(); ++i) out.x(passive[i]) = z(i);
        break;
      }
      // Step from x toward z as far as x stays ≥ 0; the columns reaching 0 leave the passive set.
      double alpha = 1;
      for (size_t i = 0; i < passive.size(); ++i)
        if (z(i) <= 0) alpha = std::min(alpha, out.x(passive[i]) / (out.x(passive[i]) - z(i)));
      for (size_t i = 0; i < passive.size(); ++i) out.x(passive[i]) += alpha * (z(i) - out.x(passive[i]));
      std::vector<int> kept;
      for (int j : passive) {
        if (out.x(j) > 0) {
          kept.push_back(j);
        } else {
          out.x(j) = 0;
          in_passive[j] = false;
        }
      }
      passive.swap(kept);
      if (passive.empty()) break;
    }
    out.residual = b - A * out.x;
  }
  return out;
}

}  // namespace contactqp::detail
