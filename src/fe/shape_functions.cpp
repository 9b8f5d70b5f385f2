#include "shape_functions.hpp"

namespace contactqp::detail {
namespace {

const QuadraturePoint kCentroid[] = {{1.0 / 3, 1.0 / 3, 0.5}};

constexpr double kA = 0.445948490915965, kWa = 0.5 * 0.223381589678011;
constexpr double kB = 0.091576213509771, kWb = 0.5 * 0.109951743655322;
const QuadraturePoint kDegree4[] = {{kA, kA, kWa}, {1 - 2 * kA, kA, kWa}, {kA, 1 - 2 * kA, kWa},
                                    {kB, kB, kWb}, {1 - 2 * kB, kB, kWb}, {kB, 1 - 2 * kB, kWb}};

}  // namespace

const double kEdgeGaussT[3] = {0.5 - 0.3872983346207417, 0.5, 0.5 + 0.3872983346207417};
const double kEdgeGaussW[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};

int triangle_rule(int order, const QuadraturePoint*& points) {
  if (order == 1) {
    points = kCentroid;
    return 1;
  }
  points = kDegree4;
  return 6;
}

Eigen::VectorXd shape_values(int order, double xi, double eta) {
  const double L0 = 1 - xi - eta, L1 = xi, L2 = eta;
  if (order == 1) return Eigen::Vector3d(L0, L1, L2);
  Eigen::VectorXd N(6);
  N << L0 * (2 * L0 - 1), L1 * (2 * L1 - 1), L2 * (2 * L2 - 1), 4 * L0 * L1, 4 * L1 * L2, 4 * L2 * L0;
  return N;
}

Eigen::Matrix<double, 2, Eigen::Dynamic> shape_gradients(int order, double xi, double eta) {
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

Eigen::Vector2d reference_node(int i) {
  static const double xi[] = {0, 1, 0, 0.5, 0.5, 0}, eta[] = {0, 0, 1, 0, 0.5, 0.5};
  return {xi[i], eta[i]};
}

EdgePoint edge_point(double t, const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d* m) {
  EdgePoint p;
  if (m) {
    p.N[0] = (1 - t) * (1 - 2 * t);
    p.N[1] = t * (2 * t - 1);
    p.N[2] = 4 * t * (1 - t);
    p.dx = (4 * t - 3) * a + (4 * t - 1) * b + (4 - 8 * t) * *m;
  } else {
    p.N[0] = 1 - t;
    p.N[1] = t;
    p.N[2] = 0;
    p.dx = b - a;
  }
  return p;
}

}  // namespace contactqp::detail
