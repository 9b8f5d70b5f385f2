#include "point_locator.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <stdexcept>
#include <utility>

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
  // Each simplex's box (its vertices', widened to the caller's).
  const int n = static_cast<int>(simplices_.size());
  boxes_.resize(n);
  Eigen::Vector3d all_low = Eigen::Vector3d::Constant(std::numeric_limits<double>::max()), all_high = -all_low;
  for (int s = 0; s < n; ++s) {
    Box& box = boxes_[s];
    box.low = box.high = vertices_[simplices_[s][0]];
    for (int k = 1; k <= dim_; ++k) {
      box.low = box.low.cwiseMin(vertices_[simplices_[s][k]]);
      box.high = box.high.cwiseMax(vertices_[simplices_[s][k]]);
    }
    if (!boxes.empty()) {
      box.low = box.low.cwiseMin(boxes[s].low);
      box.high = box.high.cwiseMax(boxes[s].high);
    }
    all_low = all_low.cwiseMin(box.low);
    all_high = all_high.cwiseMax(box.high);
  }
  const auto low = [&](int s) -> const Eigen::Vector3d& { return boxes_[s].low; };
  const auto high = [&](int s) -> const Eigen::Vector3d& { return boxes_[s].high; };
  slack_ = 1e-12 * std::max((all_high - all_low).maxCoeff(), 1e-300);
  // The hierarchy, top down: each node's simplices split at the median of their centres along
  // the longest side of the centres' box (a balanced tree: depth about log2(n / kLeaf)).
  constexpr int kLeaf = 4;
  order_.resize(n);
  for (int s = 0; s < n; ++s) order_[s] = s;
  nodes_.reserve(2 * (n / kLeaf + 1));
  nodes_.emplace_back();
  struct Range {
    int node, first, count;
  };
  std::vector<Range> pending = {{0, 0, n}};
  while (!pending.empty()) {
    const Range r = pending.back();
    pending.pop_back();
    Eigen::Vector3d box_low = low(order_[r.first]), box_high = high(order_[r.first]);
    Eigen::Vector3d centre_low = 0.5 * (box_low + box_high), centre_high = centre_low;
    for (int k = r.first + 1; k < r.first + r.count; ++k) {
      const int s = order_[k];
      box_low = box_low.cwiseMin(low(s));
      box_high = box_high.cwiseMax(high(s));
      const Eigen::Vector3d centre = 0.5 * (low(s) + high(s));
      centre_low = centre_low.cwiseMin(centre);
      centre_high = centre_high.cwiseMax(centre);
    }
    nodes_[r.node].low = box_low;
    nodes_[r.node].high = box_high;
    if (r.count <= kLeaf) {
      nodes_[r.node].first = r.first;
      nodes_[r.node].count = r.count;
      continue;
    }
    int axis = 0;
    for (int k = 1; k < dim_; ++k)
      if (centre_high[k] - centre_low[k] > centre_high[axis] - centre_low[axis]) axis = k;
    const int middle = r.first + r.count / 2;
    std::nth_element(order_.begin() + r.first, order_.begin() + middle, order_.begin() + r.first + r.count,
                     [&](int a, int b) { return low(a)[axis] + high(a)[axis] < low(b)[axis] + high(b)[axis]; });
    const int left = static_cast<int>(nodes_.size());
    nodes_[r.node].left = left;
    nodes_.emplace_back();
    nodes_.emplace_back();
    pending.push_back({left, r.first, middle - r.first});
    pending.push_back({left + 1, middle, r.first + r.count - middle});
  }
}

bool PointLocator::holds(const Eigen::Vector3d& low, const Eigen::Vector3d& high, const Eigen::Vector3d& x) const {
  return ((x - low).array() >= -slack_).all() && ((high - x).array() >= -slack_).all();
}

template <class Visit>
void PointLocator::for_each_holding(const Eigen::Vector3d& x, Visit&& visit) const {
  // Depth first on a stack of its own: Gmsh's size callback comes here for every point it
  // sizes, so no allocation per query. The median split keeps the depth near log2(n), and the
  // stack holds at most depth + 1 nodes.
  std::array<int, 128> pending;
  int top = 0;
  pending[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[pending[--top]];
    if (!holds(node.low, node.high, x)) continue;
    if (node.left < 0) {
      for (int k = node.first; k < node.first + node.count; ++k)
        if (holds(boxes_[order_[k]].low, boxes_[order_[k]].high, x)) visit(order_[k]);
    } else {
      pending[top++] = node.left;
      pending[top++] = node.left + 1;
    }
  }
}

std::vector<int> PointLocator::nearest_leaves(const Eigen::Vector3d& x) const {
  // Best first by the distance from x to a node's box; past the first leaf, the leaves within
  // that leaf's diagonal of it (as the ring of grid cells around the first one found).
  const auto distance = [&](const Node& node) { return (x.cwiseMax(node.low).cwiseMin(node.high) - x).norm(); };
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  queue.emplace(distance(nodes_[0]), 0);
  std::vector<int> leaves;
  double reach = std::numeric_limits<double>::infinity();
  while (!queue.empty() && queue.top().first <= reach) {
    const auto [d, index] = queue.top();
    queue.pop();
    const Node& node = nodes_[index];
    if (node.left < 0) {
      if (leaves.empty()) reach = d + (node.high - node.low).norm();
      leaves.push_back(index);
    } else {
      queue.emplace(distance(nodes_[node.left]), node.left);
      queue.emplace(distance(nodes_[node.left + 1]), node.left + 1);
    }
  }
  return leaves;
}

std::vector<int> PointLocator::near(const Eigen::Vector3d& x) const {
  std::vector<int> candidates;
  for_each_holding(x, [&](int s) { candidates.push_back(s); });
  if (candidates.empty())
    for (const int leaf : nearest_leaves(x))
      for (int k = nodes_[leaf].first; k < nodes_[leaf].first + nodes_[leaf].count; ++k)
        candidates.push_back(order_[k]);
  return candidates;
}

Eigen::Vector4d PointLocator::barycentric(int s, const Eigen::Vector3d& x) const {
  const Eigen::Vector3d t = inverse_[s] * (x - vertices_[simplices_[s][0]]);
  Eigen::Vector4d lambda = Eigen::Vector4d::Zero();
  lambda[0] = 1 - t.head(dim_).sum();
  for (int k = 0; k < dim_; ++k) lambda[k + 1] = t[k];
  return lambda;
}

PointLocator::Location PointLocator::locate(const Eigen::Vector3d& x) const {
  int best = -1;
  double best_margin = -std::numeric_limits<double>::infinity();
  const auto consider = [&](int s) {
    const double margin = barycentric(s, x).head(dim_ + 1).minCoeff();
    if (margin > best_margin) {
      best_margin = margin;
      best = s;
    }
  };
  for_each_holding(x, consider);
  // Outside every simplex whose box holds x (outside the mesh, or beside a curved side): the
  // least negative barycentric coordinates among the nearest leaves too.
  if (best < 0 || best_margin < -1e-12)
    for (const int leaf : nearest_leaves(x))
      for (int k = nodes_[leaf].first; k < nodes_[leaf].first + nodes_[leaf].count; ++k) consider(order_[k]);
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
