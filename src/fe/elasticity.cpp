// Linear elasticity on 3-node and 6-node triangles (isoparametric).
#include <Eigen/LU>
#include <cmath>

#include "contactqp/model.hpp"
#include "shape_functions.hpp"

namespace contactqp {

Eigen::Matrix3d elasticity_matrix(PlaneModel model, const Material& material) {
  const double E = material.E, nu = material.nu;
  Eigen::Matrix3d D;
  if (model == PlaneModel::PlaneStrain) {
    const double c = E / ((1 + nu) * (1 - 2 * nu));
    D << c * (1 - nu), c * nu, 0,
         c * nu, c * (1 - nu), 0,
         0, 0, c * (1 - 2 * nu) / 2;
  } else {
    const double c = E / (1 - nu * nu);
    D << c, c * nu, 0,
         c * nu, c, 0,
         0, 0, c * (1 - nu) / 2;
  }
  return D;
}

Eigen::MatrixXd element_stiffness(const Eigen::Vector2d* nodes, int order, const Eigen::Matrix3d& D,
                                  double thickness) {
  const int npe = order == 1 ? 3 : 6;
  Eigen::MatrixXd Ke = Eigen::MatrixXd::Zero(2 * npe, 2 * npe);
  Eigen::Matrix<double, 2, Eigen::Dynamic> X(2, npe);
  for (int i = 0; i < npe; ++i) X.col(i) = nodes[i];

  const detail::QuadraturePoint* rule = nullptr;
  const int n_points = detail::triangle_rule(order, rule);
  for (int k = 0; k < n_points; ++k) {
    const detail::QuadraturePoint& q = rule[k];
    const Eigen::Matrix<double, 2, Eigen::Dynamic> dN = detail::shape_gradients(order, q.xi, q.eta);
    const Eigen::Matrix2d J = dN * X.transpose();  // J(r, c) = d x_c / d ξ_r
    const double detJ = J.determinant();
    const Eigen::Matrix<double, 2, Eigen::Dynamic> dNdx = J.inverse() * dN;  // rows d/dx, d/dy
    Eigen::Matrix<double, 3, Eigen::Dynamic> Bm = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, 2 * npe);
    for (int i = 0; i < npe; ++i) {
      Bm(0, 2 * i) = dNdx(0, i);
      Bm(1, 2 * i + 1) = dNdx(1, i);
      Bm(2, 2 * i) = dNdx(1, i);
      Bm(2, 2 * i + 1) = dNdx(0, i);
    }
    Ke.noalias() += (q.weight * std::abs(detJ) * thickness) * (Bm.transpose() * D * Bm);
  }
  return Ke;
}

}  // namespace contactqp
