// Where a point lies in a simplex mesh, and a field given at its vertices evaluated there: what
// an adaptive run (src/run/adaptive_run.cpp) needs of a body's last mesh, for the size field it
// hands Gmsh and for the warm start of the next mesh's solve; and the cells near a point, which
// the true error of an estimate interpolates from (post/nested_difference.cpp). Gmsh asks for
// sizes at points of the new geometry, and the new mesh has nodes, that lie just outside the
// last mesh (a curved side between its nodes): those take the nearest element's closest point.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

namespace contactqp::detail {

class PointLocator {
 public:
  // A simplex's bounding box, when its cell reaches beyond its vertices' hull (a quadratic
  // cell's curved sides).
  struct Box {
    Eigen::Vector3d low, high;
  };
  // `simplices`: dim + 1 vertex indices each (the rest ignored). `boxes`: empty, or one per
  // simplex, which the grid then files it under in place of its vertices' box.
  PointLocator(int dim, std::vector<Eigen::Vector3d> vertices, std::vector<std::array<int, 4>> simplices,
               const std::vector<Box>& boxes = {});

  struct Location {
    int simplex = -1;
    Eigen::Vector4d weights = Eigen::Vector4d::Zero();  // barycentric, ≥ 0, summing to 1 (dim + 1 used)
  };
  // The simplex holding x and x's barycentric coordinates in it; outside the mesh, the simplex
  // whose barycentric coordinates at x are least negative, with them clamped to it.
  Location locate(const Eigen::Vector3d& x) const;

  // Σ_k weights_k · values[vertex k of the simplex]: the linear interpolant of vertex values.
  double interpolate(const Location& at, const std::vector<double>& values) const;
  double interpolate(const Eigen::Vector3d& x, const std::vector<double>& values) const {
    return interpolate(locate(x), values);
  }

  int n_vertices() const { return static_cast<int>(vertices_.size()); }

  // The simplices whose boxes hold x (the nearest leaf's when none does), each once: the
  // candidates for a caller that tests "inside" its own way (a curved cell's isoparametric map,
  // post/nested_difference.cpp).
  std::vector<int> near(const Eigen::Vector3d& x) const;

 private:
  // A node of the bounding-volume hierarchy: the box of its simplices' boxes; a leaf lists
  // order_[first, first + count), an inner node's children are nodes_[left] and nodes_[left + 1].
  struct Node {
    Eigen::Vector3d low, high;
    int left = -1, first = 0, count = 0;
  };
  Eigen::Vector4d barycentric(int s, const Eigen::Vector3d& x) const;
  bool holds(const Eigen::Vector3d& low, const Eigen::Vector3d& high, const Eigen::Vector3d& x) const;
  // Calls visit(simplex) for every simplex whose box holds x within slack_.
  template <class Visit>
  void for_each_holding(const Eigen::Vector3d& x, Visit&& visit) const;
  // The leaves nearest x (box distance), nearest first, up to one past the first leaf found,
  // as node indices: where x lies outside every box.
  std::vector<int> nearest_leaves(const Eigen::Vector3d& x) const;

  int dim_;
  std::vector<Eigen::Vector3d> vertices_;
  std::vector<std::array<int, 4>> simplices_;
  std::vector<Eigen::Matrix3d> inverse_;  // of each simplex's edge matrix [v1 − v0, v2 − v0, v3 − v0]
  // The hierarchy: boxes split at the median of their simplices' centres along their longest
  // side, down to a few simplices per leaf, so that a query costs about log n boxes however
  // strongly the mesh is graded (a uniform grid put 1e4 simplices of an adapted mesh's contact
  // zone in one cell).
  std::vector<Node> nodes_;
  std::vector<int> order_;  // simplices, leaf by leaf
  std::vector<Box> boxes_;  // each simplex's (its vertices', widened to the caller's)
  double slack_ = 0;        // box tolerance: round-off of the mesh's extent
};

}  // namespace contactqp::detail
