// bound_transform() (bound_transform.hpp).
#include "bound_transform.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace contactqp::detail {

bool bound_transform(const Eigen::MatrixXd& rows, Eigen::MatrixXd& T, Eigen::MatrixXd& Q) {
  const Eigen::Index r = rows.rows(), c = rows.cols();
  if (r > c) return false;
  // T = [rows of B; an orthonormal basis of the complement of their span].
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(rows.transpose());
  const Eigen::MatrixXd basis = qr.householderQ();  // c × c, orthogonal
  T.resize(c, c);
  T.topRows(r) = rows;
  if (c > r) T.bottomRows(c - r) = basis.rightCols(c - r).transpose();
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(T);
  // |det T| ≤ the product of its row lengths (Hadamard), with equality for orthogonal rows:
  // their ratio measures how far the rows are from dependent.
  if (lu.rank() < c || std::abs(lu.determinant()) < 1e-8 * T.rowwise().norm().prod()) return false;
  Q = lu.inverse();
  return true;
}

}  // namespace contactqp::detail
