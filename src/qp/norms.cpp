#include "norms.hpp"

#include <algorithm>
#include <cmath>

namespace contactqp {

double inf_norm(const Eigen::VectorXd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

double infinity_norm(const Eigen::SparseMatrix<double>& A) {
  Eigen::VectorXd row_sums = Eigen::VectorXd::Zero(A.rows());
  for (int j = 0; j < A.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it) row_sums(it.row()) += std::abs(it.value());
  return row_sums.size() == 0 ? 0.0 : row_sums.maxCoeff();
}

double relative(double x, double scale) { return scale > 0 ? x / scale : x; }

double relative_error(double a, double b) { return relative(std::abs(a - b), std::abs(b)); }

double relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return relative((a - b).norm(), b.norm());
}

double relative_difference_inf(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return relative(inf_norm(a - b), inf_norm(b));
}

double symmetric_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const double scale = std::max(a.norm(), b.norm());
  return scale > 0 ? (a - b).norm() / scale : 0.0;
}

}  // namespace contactqp
