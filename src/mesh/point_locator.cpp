#include "point_locator.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace contactqp::detail {

PointLocator::PointLocator(int dim, std::vector<Eigen::Vector3d> vertices, std::vector<std::array<int, 4>> simplices,
                           const std::vector<Box>& boxes)
    : dim_(dim), vertices_(std::move(vertices)), simplices_(std::move(simplices)) {
  if (simplices_.empty()) throw std::invalid_argument("PointLocator: no mesh");
  if (!boxes.empty() && boxes.size() != simplices_.size())
    throw std::invalid_argument("PointLocator: one box per simplex, or none");
  inverse_.reserve(simplices_.size());
  for (const auto& s : simplices_) {
    Eigen::Matrix3d edges = Eigen::Matrix3d::Identity();  // 2D: the z column stays e_z
    for (int k = 0; k < dim_; ++k) edges.col(k) = vertices_[s[k + 1]] - vertices_[s[0]];
    inverse_.push_back(edges.inverse());
  }
  low_ = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector3d high = -low_;
  for (const Eigen::Vector3d& v : vertices_) {
    low_ = low_.cwiseMin(v);
    high = high.cwiseMax(v);
  }
  for (const Box& box : boxes) {
    low_ = low_.cwiseMin(box.low);
    high = high.cwiseMax(box.high);
  }
  // About one simplex per cell.
  const double extent = (high - low_).head(dim_).maxCoeff();
  const double target = extent / std::max(1.0, std::pow(static_cast<double>(simplices_.size()), 1.0 / dim_));
  for (int k = 0; k < 3; ++k) {
    cells_[k] = k < dim_ ? std::clamp(static_cast<int>(std::ceil((high[k] - low_[k]) / target)), 1, 4096) : 1;
    cell_size_[k] = k < dim_ ? std::max((high[k] - low_[k]) / cells_[k], 1e-300) : 1.0;
  }
  const std::size_t n_cells = static_cast<std::size_t>(cells_[0]) * cells_[1] * cells_[2];
  // Two passes: count, then fill.
  std::vector<int> count(n_cells + 1, 0);
  auto for_cells = [&](int simplex, auto&& visit) {
    const std::array<int, 4>& s = simplices_[simplex];
    Eigen::Vector3d lo = vertices_[s[0]], hi = lo;
    for (int k = 1; k <= dim_; ++k) {
      lo = lo.cwiseMin(vertices_[s[k]]);
      hi = hi.cwiseMax(vertices_[s[k]]);
    }
    if (!boxes.empty()) {
      lo = lo.cwiseMin(boxes[simplex].low);
      hi = hi.cwiseMax(boxes[simplex].high);
    }
    const std::array<int, 3> a = cell_of(lo), b = cell_of(hi);
    for (int i = a[0]; i <= b[0]; ++i)
      for (int j = a[1]; j <= b[1]; ++j)
        for (int l = a[2]; l <= b[2]; ++l) visit((static_cast<std::size_t>(l) * cells_[1] + j) * cells_[0] + i);
  };
  const int n_simplices = static_cast<int>(simplices_.size());
  for (int s = 0; s < n_simplices; ++s) for_cells(s, [&](std::size_t c) { ++count[c + 1]; });
  for (std::size_t c = 0; c < n_cells; ++c) count[c + 1] += count[c];
  cell_start_ = count;
  cell_simplices_.resize(count.back());
  for (int s = 0; s < n_simplices; ++s) for_cells(s, [&](std::size_t c) { cell_simplices_[count[c]++] = s; });
}

std::array<int, 3> PointLocator::cell_of(const Eigen::Vector3d& x) const {
  std::array<int, 3> cell{0, 0, 0};
  for (int k = 0; k < dim_; ++k)
    cell[k] = std::clamp(static_cast<int>(std::floor((x[k] - low_[k]) / cell_size_[k])), 0, cells_[k] - 1);
  return cell;
}

Eigen::Vector4d PointLocator::barycentric(int s, const Eigen::Vector3d& x) const {
  const Eigen::Vector3d t = inverse_[s] * (x - vertices_[simplices_[s][0]]);
  Eigen::Vector4d lambda = Eigen::Vector4d::Zero();
  lambda[0] = 1 - t.head(dim_).sum();
  for (int k = 0; k < dim_; ++k) lambda[k + 1] = t[k];
  return lambda;
}

PointLocator::Location PointLocator::locate(const Eigen::Vector3d& x) const {
  const std::array<int, 3> home = cell_of(x);
  int best = -1;
  double best_margin = -std::numeric_limits<double>::infinity();
  // Rings of cells around x's cell, outward, until a simplex holds x, or a ring past the one
  // where the closest candidate so far was found has been searched too.
  const int max_ring = *std::max_element(cells_.begin(), cells_.end());
  int found_ring = -1;
  for (int ring = 0; ring <= max_ring; ++ring) {
    for (int i = home[0] - ring; i <= home[0] + ring; ++i)
      for (int j = home[1] - ring; j <= home[1] + ring; ++j)
        for (int l = home[2] - ring; l <= home[2] + ring; ++l) {
          if (i < 0 || j < 0 || l < 0 || i >= cells_[0] || j >= cells_[1] || l >= cells_[2]) continue;
          if (std::max({std::abs(i - home[0]), std::abs(j - home[1]), std::abs(l - home[2])}) != ring) continue;
          const std::size_t c = (static_cast<std::size_t>(l) * cells_[1] + j) * cells_[0] + i;
          for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
            const int s = cell_simplices_[k];
            const double margin = barycentric(s, x).head(dim_ + 1).minCoeff();
            if (margin > best_margin) {
              best_margin = margin;
              best = s;
            }
          }
        }
    if (best >= 0 && best_margin >= -1e-12) break;
    if (best >= 0 && found_ring < 0) found_ring = ring;
    if (found_ring >= 0 && ring > found_ring) break;
  }
  Location at;
  at.simplex = best;
  at.weights = barycentric(best, x).cwiseMax(0.0);
  at.weights.tail(3 - dim_).setZero();
  at.weights /= at.weights.sum();
  return at;
}

double PointLocator::interpolate(const Location& at, const std::vector<double>& values) const {
  double value = 0;
  for (int k = 0; k <= dim_; ++k) value += at.weights[k] * values[simplices_[at.simplex][k]];
  return value;
}

}  // namespace contactqp::detail
