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
#include "mesh/point_locator.hpp"
#include "mesh/shape_functions.hpp"

namespace contactqp {
namespace {

// The coarse mesh's cells for locating points: each filed under the box of all its nodes (a
// quadratic cell's curved sides reach beyond its vertices' box).
detail::PointLocator cell_locator(const Mesh& mesh) {
  const int n = mesh.n_elements(), npe = mesh.nodes_per_element(), dim = mesh.dim;
  std::vector<std::array<int, 4>> simplices(n, std::array<int, 4>{0, 0, 0, 0});
  std::vector<detail::PointLocator::Box> boxes(n);
  for (int e = 0; e < n; ++e) {
    const int* v = mesh.element(e);
    for (int k = 0; k <= dim; ++k) simplices[e][k] = v[k];
    boxes[e].low = boxes[e].high = mesh.nodes[v[0]];
    for (int i = 1; i < npe; ++i) {
      boxes[e].low = boxes[e].low.cwiseMin(mesh.nodes[v[i]]);
      boxes[e].high = boxes[e].high.cwiseMax(mesh.nodes[v[i]]);
    }
  }
  return detail::PointLocator(dim, mesh.nodes, std::move(simplices), boxes);
}

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
  const detail::PointLocator locator = cell_locator(mesh);
  const int npe = mesh.nodes_per_element();
  Eigen::VectorXd d = Eigen::VectorXd::Zero(fine_qp.n_dofs());
  Eigen::MatrixXd at_dofs = Eigen::MatrixXd::Zero(fine.rigid_rotations.empty() ? 0 : dim * fine.mesh.n_nodes(), 1);
  for (int node = 0; node < fine.mesh.n_nodes(); ++node) {
    const Eigen::Matrix<double, dim, 1> x = fine.mesh.nodes[node].head<dim>();
    // The element holding x, or the one it lies least outside of (a fine node on a curved side
    // that the coarse side cuts off).
    // Only the node's own body's elements: where two bodies touch, a point of one lies on the
    // other's boundary too, and the two move differently.
    const int body = fine.body_of_node(node);
    int best = -1;
    double best_outside = std::numeric_limits<double>::infinity();
    Eigen::Matrix<double, dim, 1> xi, best_xi;
    const auto consider = [&](int e) {
      if (body_of_element(coarse, e) != body) return false;
      const double outside = locate<dim>(mesh, e, x, xi);
      if (outside < best_outside) {
        best_outside = outside;
        best = e;
        best_xi = xi;
      }
      return outside == 0;
    };
    for (const int e : locator.near(fine.mesh.nodes[node]))
      if (consider(e)) break;
    if (best < 0) {  // no box of the body's cells holds x: the cell whose vertices x lies nearest
      consider(locator.locate(fine.mesh.nodes[node]).simplex);
      if (best < 0)  // it was another body's: the body's cell x lies least outside of
        for (int e = 0; e < mesh.n_elements(); ++e)
          if (consider(e)) break;
    }
    const Eigen::VectorXd N = detail::cell_values<dim>(mesh.order, best_xi);
    Eigen::Matrix<double, dim, 1> value = Eigen::Matrix<double, dim, 1>::Zero();
    for (int i = 0; i < npe; ++i) value += N[i] * displacement.segment<dim>(dim * mesh.element(best)[i]);
    for (int c = 0; c < dim; ++c) {
      const int column = fine.free_index[dim * node + c];
      if (column >= 0) d[column] = value[c] - reference[dim * node + c];
      if (at_dofs.rows() > 0) at_dofs(dim * node + c, 0) = value[c] - reference[dim * node + c];
    }
  }
  if (at_dofs.rows() > 0) {  // a turning surface: its translations and angles, fitted to its nodes
    Eigen::MatrixXd columns = d;
    fit_turning_surfaces(fine, at_dofs, columns);
    d = columns.col(0);
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
