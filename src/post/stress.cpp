// Stress recovery: σ = D ε at each element's nodes, averaged at shared nodes.
#include <Eigen/LU>
#include <cmath>

#include "../fe/shape_functions.hpp"
#include "contactqp/post.hpp"

namespace contactqp {

NodalStress nodal_stresses(const Model& model, const Eigen::VectorXd& displacement) {
  const Mesh& mesh = model.mesh;
  const int n = mesh.n_nodes(), npe = mesh.nodes_per_element();
  const Eigen::Matrix3d D = elasticity_matrix(model.scene.model, model.scene.material);
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(3, n);  // σxx, σyy, σxy weighted by area
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(n);
  Eigen::Matrix<double, 2, Eigen::Dynamic> X(2, npe), U(2, npe);
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    for (int i = 0; i < npe; ++i) {
      X.col(i) = mesh.nodes[v[i]];
      U.col(i) = displacement.segment<2>(2 * v[i]);
    }
    const double area = std::abs(element_area(mesh, e));
    for (int i = 0; i < npe; ++i) {
      const Eigen::Vector2d at = detail::reference_node(i);
      const Eigen::Matrix<double, 2, Eigen::Dynamic> dN = detail::shape_gradients(mesh.order, at.x(), at.y());
      const Eigen::Matrix2d J = dN * X.transpose();          // J(r, c) = d x_c / d ξ_r
      const Eigen::Matrix2d grad = (J.inverse() * dN * U.transpose()).transpose();  // grad(a, b) = d u_a / d x_b
      const Eigen::Vector3d strain(grad(0, 0), grad(1, 1), grad(0, 1) + grad(1, 0));
      sum.col(v[i]) += area * (D * strain);
      weight[v[i]] += area;
    }
  }
  NodalStress stress;
  stress.xx.resize(n);
  stress.yy.resize(n);
  stress.xy.resize(n);
  stress.zz.resize(n);
  stress.von_mises.resize(n);
  const double nu = model.scene.model == PlaneModel::PlaneStrain ? model.scene.material.nu : 0.0;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d s = weight[k] > 0 ? Eigen::Vector3d(sum.col(k) / weight[k]) : Eigen::Vector3d::Zero();
    const double zz = nu * (s[0] + s[1]);
    stress.xx[k] = s[0];
    stress.yy[k] = s[1];
    stress.xy[k] = s[2];
    stress.zz[k] = zz;
    stress.von_mises[k] = std::sqrt(0.5 * ((s[0] - s[1]) * (s[0] - s[1]) + (s[1] - zz) * (s[1] - zz) + (zz - s[0]) * (zz - s[0])) +
                                    3 * s[2] * s[2]);
  }
  return stress;
}

}  // namespace contactqp
