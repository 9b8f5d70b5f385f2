// The energy norm of the difference of two solutions on nested meshes (estimate.hpp): the true
// error of a coarse solution against a finer reference, for measuring the estimate's effectivity.
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "contactqp/estimate.hpp"
#include "mesh/shape_functions.hpp"

namespace contactqp {
namespace {

// Buckets of the coarse elements' bounding boxes on a uniform grid, for locating points.
template <int dim>
class ElementGrid {
 public:
  explicit ElementGrid(const Mesh& mesh) : mesh_(mesh) {
    const int n = mesh.n_elements(), npe = mesh.nodes_per_element();
    lower_ = upper_ = mesh.nodes[0].head<dim>();
    for (const Eigen::Vector3d& x : mesh.nodes) {
      lower_ = lower_.cwiseMin(x.head<dim>());
      upper_ = upper_.cwiseMax(x.head<dim>());
    }
    const double cells = std::max(1.0, std::pow(static_cast<double>(n), 1.0 / dim));
    for (int c = 0; c < dim; ++c) {
      count_[c] = static_cast<int>(cells);
      width_[c] = std::max((upper_[c] - lower_[c]) / count_[c], 1e-300);
    }
    int total = 1;
    for (int c = 0; c < dim; ++c) total *= count_[c];
    buckets_.resize(total);
    for (int e = 0; e < n; ++e) {
      Eigen::Matrix<double, dim, 1> lo = mesh.nodes[mesh.element(e)[0]].head<dim>(), hi = lo;
      for (int i = 1; i < npe; ++i) {
        lo = lo.cwiseMin(mesh.nodes[mesh.element(e)[i]].head<dim>());
        hi = hi.cwiseMax(mesh.nodes[mesh.element(e)[i]].head<dim>());
      }
      std::array<int, 3> a{}, b{};
      for (int c = 0; c < dim; ++c) {
        a[c] = cell(lo[c] - 1e-9 * width_[c], c);
        b[c] = cell(hi[c] + 1e-9 * width_[c], c);
      }
      for (int i = a[0]; i <= b[0]; ++i)
        for (int j = a[1]; j <= b[1]; ++j)
          for (int k = (dim == 3 ? a[2] : 0); k <= (dim == 3 ? b[2] : 0); ++k) buckets_[index(i, j, k)].push_back(e);
    }
  }
  // The elements whose boxes may hold x (the nearest bucket's when x lies outside the grid).
  const std::vector<int>& near(const Eigen::Matrix<double, dim, 1>& x) const {
    std::array<int, 3> a{};
    for (int c = 0; c < dim; ++c) a[c] = cell(x[c], c);
    return buckets_[index(a[0], a[1], a[2])];
  }

 private:
  int cell(double x, int c) const {
    return std::clamp(static_cast<int>(std::floor((x - lower_[c]) / width_[c])), 0, count_[c] - 1);
  }
  int index(int i, int j, int k) const { return (k * (dim == 3 ? count_[1] : 1) + j) * count_[0] + i; }

  const Mesh& mesh_;
  Eigen::Matrix<double, dim, 1> lower_, upper_, width_;
  std::array<int, 3> count_{{1, 1, 1}};
  std::vector<std::vector<int>> buckets_;
};

// The reference point of x in element e by Newton's method on the isoparametric map, and how far
// it lies outside the reference cell (0 inside).
template <int dim>
double locate(const Mesh& mesh, int e, const Eigen::Matrix<double, dim, 1>& x, Eigen::Matrix<double, dim, 1>& xi) {
  const int npe = mesh.nodes_per_element();
  Eigen::Matrix<double, dim, Eigen::Dynamic> X(dim, npe);
  for (int i = 0; i < npe; ++i) X.col(i) = mesh.nodes[mesh.element(e)[i]].head<dim>();
  xi.setConstant(1.0 / (dim + 1));
  for (int iteration = 0; iteration < 8; ++iteration) {
    const Eigen::VectorXd N = detail::cell_values<dim>(mesh.order, xi);
    const Eigen::Matrix<double, dim, Eigen::Dynamic> dN = detail::cell_gradients<dim>(mesh.order, xi);
    const Eigen::Matrix<double, dim, 1> residual = X * N - x;
    const Eigen::Matrix<double, dim, dim> J = X * dN.transpose();  // J(c, r) = dx_c/dξ_r
    xi -= J.inverse() * residual;
    if (residual.norm() <= 1e-14 * (X.col(1) - X.col(0)).norm()) break;
  }
  double outside = std::max(0.0, -xi.minCoeff());
  outside = std::max(outside, xi.sum() - 1.0);
  return outside;
}

template <int dim>
double distance(const Model& coarse, const Eigen::VectorXd& u_coarse, const Model& fine,
                const QuadraticProgram& fine_qp, const Eigen::VectorXd& u_fine) {
  const Mesh& mesh = coarse.mesh;
  const Eigen::VectorXd displacement = full_displacement(coarse, u_coarse);
  const Eigen::VectorXd reference = full_displacement(fine, u_fine);
  const ElementGrid<dim> grid(mesh);
  const int npe = mesh.nodes_per_element();
  Eigen::VectorXd d = Eigen::VectorXd::Zero(fine_qp.n_dofs());
  for (int node = 0; node < fine.mesh.n_nodes(); ++node) {
    const Eigen::Matrix<double, dim, 1> x = fine.mesh.nodes[node].head<dim>();
    // The element holding x, or the one it lies least outside of (a fine node on a curved side
    // that the coarse side cuts off).
    int best = -1;
    double best_outside = std::numeric_limits<double>::infinity();
    Eigen::Matrix<double, dim, 1> xi, best_xi;
    for (int e : grid.near(x)) {
      const double outside = locate<dim>(mesh, e, x, xi);
      if (outside < best_outside) {
        best_outside = outside;
        best = e;
        best_xi = xi;
      }
      if (outside == 0) break;
    }
    if (best < 0) continue;
    const Eigen::VectorXd N = detail::cell_values<dim>(mesh.order, best_xi);
    Eigen::Matrix<double, dim, 1> value = Eigen::Matrix<double, dim, 1>::Zero();
    for (int i = 0; i < npe; ++i) value += N[i] * displacement.segment<dim>(dim * mesh.element(best)[i]);
    for (int c = 0; c < dim; ++c) {
      const int column = fine.free_index[dim * node + c];
      if (column >= 0) d[column] = value[c] - reference[dim * node + c];
    }
  }
  return std::sqrt(std::max(0.0, d.dot(fine_qp.K * d)));
}

}  // namespace

double energy_distance(const Model& coarse, const Eigen::VectorXd& u_coarse, const Model& fine,
                       const QuadraticProgram& fine_qp, const Eigen::VectorXd& u_fine) {
  if (!coarse.frame_of_node.empty() || !fine.frame_of_node.empty())
    throw std::invalid_argument("energy_distance: DOF frames other than the global axes are not supported");
  if (coarse.dim != fine.dim) throw std::invalid_argument("energy_distance: the two models differ in dimension");
  return coarse.dim == 2 ? distance<2>(coarse, u_coarse, fine, fine_qp, u_fine)
                         : distance<3>(coarse, u_coarse, fine, fine_qp, u_fine);
}

}  // namespace contactqp
