// Where a point lies in a simplex mesh, and a field given at its vertices evaluated there: what
// an adaptive run (src/run/adaptive_run.cpp) needs of a body's last mesh, for the size field it
// hands Gmsh and for the warm start of the next mesh's solve; and the cells near a point, which
// the true error of an estimate interpolates from (post/nested_difference.cpp). Gmsh asks for
// sizes at points of the new geometry, and the new mesh has nodes, that lie just outside the
// last mesh (a curved side between its nodes): those take the nearest element's closest point.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <utility>
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

  // The simplices whose boxes meet the grid cell holding x (the nearest cell when x lies outside
  // the grid), as [first, last): the candidates for a caller that tests "inside" its own way
  // (a curved cell's isoparametric map, post/nested_difference.cpp).
  std::pair<const int*, const int*> near(const Eigen::Vector3d& x) const {
    const std::array<int, 3> c = cell_of(x);
    const std::size_t k = (static_cast<std::size_t>(c[2]) * cells_[1] + c[1]) * cells_[0] + c[0];
    return {cell_simplices_.data() + cell_start_[k], cell_simplices_.data() + cell_start_[k + 1]};
  }

 private:
  Eigen::Vector4d barycentric(int s, const Eigen::Vector3d& x) const;
  std::array<int, 3> cell_of(const Eigen::Vector3d& x) const;

  int dim_;
  std::vector<Eigen::Vector3d> vertices_;
  std::vector<std::array<int, 4>> simplices_;
  std::vector<Eigen::Matrix3d> inverse_;  // of each simplex's edge matrix [v1 − v0, v2 − v0, v3 − v0]
  // A uniform grid over the bounding box: each cell lists the simplices whose boxes meet it (CSR).
  Eigen::Vector3d low_, cell_size_;
  std::array<int, 3> cells_{1, 1, 1};
  std::vector<int> cell_start_, cell_simplices_;
};

}  // namespace contactqp::detail
