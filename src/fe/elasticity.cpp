// Linear elasticity on 3-node and 6-node triangles (isoparametric).
#include <Eigen/LU>
#include <cmath>

#include "contactqp/model.hpp"

namespace contactqp {
namespace {

struct QuadraturePoint {
  double xi, eta, weight;  // on the reference triangle (0,0), (1,0), (0,1); weights sum to ½
};

// Centroid rule: exact for the constant strain of a straight 3-node triangle.
const QuadraturePoint kCentroid[] = {{1.0 / 3, 1.0 / 3, 0.5}};

// Dunavant's 6-point rule, degree 4: exact for straight 6-node triangles (degree-2
// integrand) and accurate for curved ones.
constexpr double kA = 0.445948490915965, kWa = 0.5 * 0.223381589678011;
constexpr double kB = 0.091576213509771, kWb = 0.5 * 0.109951743655322;
const QuadraturePoint kDegree4[] = {{kA, kA, kWa}, {1 - 2 * kA, kA, kWa}, {kA, 1 - 2 * kA, kWa},
                                    {kB, kB, kWb}, {1 - 2 * kB, kB, kWb}, {kB, 1 - 2 * kB, kWb}};

// Derivatives of the shape functions with respect to (ξ, η) at one point: row 0 d/dξ, row 1 d/dη.
Eigen::Matrix<double, 2, Eigen::Dynamic> reference_gradients(int order, double xi, double eta) {
  if (order == 1) {
    Eigen::Matrix<double, 2, Eigen::Dynamic> dN(2, 3);
    dN << -1, 1, 0,
          -1, 0, 1;
    return dN;
  }
  // Barycentric L0 = 1 − ξ − η, L1 = ξ, L2 = η; N = L0(2L0−1), L1(2L1−1), L2(2L2−1), 4L0L1, 4L1L2, 4L2L0.
  const double L0 = 1 - xi - eta, L1 = xi, L2 = eta;
  Eigen::Matrix<double, 2, Eigen::Dynamic> dN(2, 6);
  dN << -(4 * L0 - 1), 4 * L1 - 1, 0, 4 * (L0 - L1), 4 * L2, -4 * L2,
        -(4 * L0 - 1), 0, 4 * L2 - 1, -4 * L1, 4 * L1, 4 * (L0 - L2);
  return dN;
}

}  // namespace

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

  auto accumulate = [&](const QuadraturePoint& q) {
    const Eigen::Matrix<double, 2, Eigen::Dynamic> dN = reference_gradients(order, q.xi, q.eta);
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
  };
  if (order == 1)
    for (const auto& q : kCentroid) accumulate(q);
  else
    for (const auto& q : kDegree4) accumulate(q);
  return Ke;
}

}  // namespace contactqp
