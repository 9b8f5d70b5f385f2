#include "fitted_curvature.hpp"
#include "qp/dense_decompositions.hpp"

#include <algorithm>
#include <cmath>

namespace contactqp {

std::optional<double> fitted_curvature(const std::vector<Eigen::Vector3d>& points, int dim,
                                       const Eigen::Vector3d& towards) {
  if (static_cast<int>(points.size()) < (dim == 2 ? 4 : 6)) return std::nullopt;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& x : points) mean += x;
  mean /= static_cast<double>(points.size());
  double scale = 0;
  for (const auto& x : points) scale = std::max(scale, (x - mean).norm());
  if (!(scale > 0)) return std::nullopt;
  const int unknowns = dim + 2;
  Eigen::MatrixXd M(points.size(), unknowns);
  for (size_t k = 0; k < points.size(); ++k) {
    const Eigen::Vector3d y = (points[k] - mean) / scale;
    M(k, 0) = y.squaredNorm();
    for (int c = 0; c < dim; ++c) M(k, 1 + c) = y[c];
    M(k, unknowns - 1) = 1.0;
  }
  const Eigen::VectorXd c = Eigen::JacobiSVD<Eigen::MatrixXd>(M, Eigen::ComputeFullV).matrixV().col(unknowns - 1);
  const double A = c[0], F = c[unknowns - 1];
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();
  for (int k = 0; k < dim; ++k) linear[k] = c[1 + k];
  const double gradient =
      std::sqrt(std::max(0.0, linear.squaredNorm() - 4 * A * F));  // |∇(A|y|² + D·y + F)| on the surface
  if (!(gradient > 0)) return std::nullopt;
  // ∇ at the centroid (y = 0) is D; the body is convex when the side where the form is negative
  // (inside the circle for A > 0) is away from what it touches, i.e. ∇ points at it.
  const double sign = linear.dot(towards) >= 0 ? 1.0 : -1.0;
  return sign * 2 * A / gradient / scale;
}

}  // namespace contactqp
