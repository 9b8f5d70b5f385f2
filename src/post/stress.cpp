// Stress recovery: σ = D ε at each element's nodes, averaged at shared nodes. With the mixed
// formulation σ = D_dev ε + p m, p = k·mean(tr ε) the element's condensed mean stress.
#include <Eigen/LU>
#include <cmath>

#include "../fe/shape_functions.hpp"
#include "contactqp/post.hpp"

namespace contactqp {

NodalStress nodal_stresses(const Model& model, const Eigen::VectorXd& displacement) {
  const Mesh& mesh = model.mesh;
  const int n = mesh.n_nodes(), npe = mesh.nodes_per_element();
  const ElementLaw law = element_law(model.scene);
  const bool mixed = law.formulation == Formulation::Mixed;
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(4, n);  // σxx, σyy, σxy, σzz weighted by area
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(n);
  Eigen::Matrix<double, 2, Eigen::Dynamic> X(2, npe), U(2, npe);
  std::vector<Eigen::Vector2d> nodes(npe);
  Eigen::VectorXd ue(2 * npe);
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    for (int i = 0; i < npe; ++i) {
      nodes[i] = mesh.nodes[v[i]];
      X.col(i) = nodes[i];
      U.col(i) = displacement.segment<2>(2 * v[i]);
      ue.segment<2>(2 * i) = U.col(i);
    }
    const double area = std::abs(element_area(mesh, e));
    const double pressure = mixed ? law.bulk * element_mean_dilatation(nodes.data(), mesh.order, ue) : 0.0;
    for (int i = 0; i < npe; ++i) {
      const Eigen::Vector2d at = detail::reference_node(i);
      const Eigen::Matrix<double, 2, Eigen::Dynamic> dN = detail::shape_gradients(mesh.order, at.x(), at.y());
      const Eigen::Matrix2d J = dN * X.transpose();          // J(r, c) = d x_c / d ξ_r
      const Eigen::Matrix2d grad = (J.inverse() * dN * U.transpose()).transpose();  // grad(a, b) = d u_a / d x_b
      const Eigen::Vector3d strain(grad(0, 0), grad(1, 1), grad(0, 1) + grad(1, 0));
      Eigen::Vector4d s;
      s.head<3>() = law.D * strain;
      if (mixed) {
        // σzz = p + 2μ(εzz − tr ε/3) with εzz = 0 in plane strain.
        s[0] += pressure;
        s[1] += pressure;
        s[3] = pressure - 2 * law.shear * (strain[0] + strain[1]) / 3;
      } else {
        s[3] = law.model == PlaneModel::PlaneStrain ? law.nu * (s[0] + s[1]) : 0.0;
      }
      sum.col(v[i]) += area * s;
      weight[v[i]] += area;
    }
  }
  NodalStress stress;
  stress.xx.resize(n);
  stress.yy.resize(n);
  stress.xy.resize(n);
  stress.zz.resize(n);
  stress.von_mises.resize(n);
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector4d s = weight[k] > 0 ? Eigen::Vector4d(sum.col(k) / weight[k]) : Eigen::Vector4d::Zero();
    const double zz = s[3];
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
