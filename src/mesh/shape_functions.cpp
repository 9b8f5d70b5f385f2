#include "mesh/shape_functions.hpp"

namespace contactqp::detail {
namespace {

const QuadraturePoint kCentroid[] = {{1.0 / 3, 1.0 / 3, 0.5}};

constexpr double kA = 0.445948490915965, kWa = 0.5 * 0.223381589678011;
constexpr double kB = 0.091576213509771, kWb = 0.5 * 0.109951743655322;
const QuadraturePoint kDegree4[] = {{kA, kA, kWa}, {1 - 2 * kA, kA, kWa}, {kA, 1 - 2 * kA, kWa},
                                    {kB, kB, kWb}, {1 - 2 * kB, kB, kWb}, {kB, 1 - 2 * kB, kWb}};

const TetrahedronPoint kTetCentroid[] = {{0.25, 0.25, 0.25, 1.0 / 6}};
constexpr double kTa = 0.5854101966249685, kTb = 0.1381966011250105, kTw = 1.0 / 24;
const TetrahedronPoint kTetDegree2[] = {
    {kTb, kTb, kTb, kTw}, {kTa, kTb, kTb, kTw}, {kTb, kTa, kTb, kTw}, {kTb, kTb, kTa, kTw}};

// The vertex pairs of the mid-edge nodes 4–9.
constexpr int kEdge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};

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
    dN << -1, 1, 0, -1, 0, 1;
    return dN;
  }
  // Barycentric L0 = 1 − ξ − η, L1 = ξ, L2 = η; N = L0(2L0−1), L1(2L1−1), L2(2L2−1), 4L0L1, 4L1L2, 4L2L0.
  const double L0 = 1 - xi - eta, L1 = xi, L2 = eta;
  Eigen::Matrix<double, 2, Eigen::Dynamic> dN(2, 6);
  dN << -(4 * L0 - 1), 4 * L1 - 1, 0, 4 * (L0 - L1), 4 * L2, -4 * L2, -(4 * L0 - 1), 0, 4 * L2 - 1, -4 * L1, 4 * L1,
      4 * (L0 - L2);
  return dN;
}

Eigen::Vector2d reference_node(int i) {
  static const double xi[] = {0, 1, 0, 0.5, 0.5, 0}, eta[] = {0, 0, 1, 0, 0.5, 0.5};
  return {xi[i], eta[i]};
}

EdgePoint edge_point(double t, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d* m) {
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

int tetrahedron_rule(int order, const TetrahedronPoint*& points) {
  if (order == 1) {
    points = kTetCentroid;
    return 1;
  }
  points = kTetDegree2;
  return 4;
}

Eigen::VectorXd tetrahedron_values(int order, double xi, double eta, double zeta) {
  const double L[4] = {1 - xi - eta - zeta, xi, eta, zeta};
  if (order == 1) return Eigen::Vector4d(L[0], L[1], L[2], L[3]);
  Eigen::VectorXd N(10);
  for (int i = 0; i < 4; ++i) N[i] = L[i] * (2 * L[i] - 1);
  for (int k = 0; k < 6; ++k) N[4 + k] = 4 * L[kEdge[k][0]] * L[kEdge[k][1]];
  return N;
}

Eigen::Matrix<double, 3, Eigen::Dynamic> tetrahedron_gradients(int order, double xi, double eta, double zeta) {
  // Barycentric L0 = 1 − ξ − η − ζ, L1 = ξ, L2 = η, L3 = ζ and their constant gradients.
  Eigen::Matrix<double, 3, 4> dL;
  dL << -1, 1, 0, 0, -1, 0, 1, 0, -1, 0, 0, 1;
  if (order == 1) return dL;
  const double L[4] = {1 - xi - eta - zeta, xi, eta, zeta};
  Eigen::Matrix<double, 3, Eigen::Dynamic> dN(3, 10);
  for (int i = 0; i < 4; ++i) dN.col(i) = (4 * L[i] - 1) * dL.col(i);
  for (int k = 0; k < 6; ++k) {
    const int a = kEdge[k][0], b = kEdge[k][1];
    dN.col(4 + k) = 4 * (L[b] * dL.col(a) + L[a] * dL.col(b));
  }
  return dN;
}

Eigen::Vector3d reference_tetrahedron_node(int i) {
  static const double vertex[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  if (i < 4) return {vertex[i][0], vertex[i][1], vertex[i][2]};
  const int a = kEdge[i - 4][0], b = kEdge[i - 4][1];
  return 0.5 * (Eigen::Vector3d(vertex[a][0], vertex[a][1], vertex[a][2]) +
                Eigen::Vector3d(vertex[b][0], vertex[b][1], vertex[b][2]));
}

template <>
std::vector<CellPoint<2>> cell_rule<2>(int order) {
  const QuadraturePoint* points = nullptr;
  const int n = triangle_rule(order, points);
  std::vector<CellPoint<2>> rule;
  for (int k = 0; k < n; ++k) rule.push_back({Eigen::Vector2d(points[k].xi, points[k].eta), points[k].weight});
  return rule;
}

template <>
std::vector<CellPoint<3>> cell_rule<3>(int order) {
  const TetrahedronPoint* points = nullptr;
  const int n = tetrahedron_rule(order, points);
  std::vector<CellPoint<3>> rule;
  for (int k = 0; k < n; ++k)
    rule.push_back({Eigen::Vector3d(points[k].xi, points[k].eta, points[k].zeta), points[k].weight});
  return rule;
}

template <>
Eigen::VectorXd cell_values<2>(int order, const Eigen::Vector2d& xi) {
  return shape_values(order, xi.x(), xi.y());
}

template <>
Eigen::VectorXd cell_values<3>(int order, const Eigen::Vector3d& xi) {
  return tetrahedron_values(order, xi.x(), xi.y(), xi.z());
}

template <>
Eigen::Matrix<double, 2, Eigen::Dynamic> cell_gradients<2>(int order, const Eigen::Vector2d& xi) {
  return shape_gradients(order, xi.x(), xi.y());
}

template <>
Eigen::Matrix<double, 3, Eigen::Dynamic> cell_gradients<3>(int order, const Eigen::Vector3d& xi) {
  return tetrahedron_gradients(order, xi.x(), xi.y(), xi.z());
}

template <>
Eigen::Vector2d cell_node<2>(int i) {
  return reference_node(i);
}

template <>
Eigen::Vector3d cell_node<3>(int i) {
  return reference_tetrahedron_node(i);
}

}  // namespace contactqp::detail
