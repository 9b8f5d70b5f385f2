// Shape functions and quadrature of the element types (3- and 6-node triangles, 4- and
// 10-node tetrahedra) and of their faces (edges in 2D, triangles in 3D), shared by the
// stiffness, the loads, the contact geometry and the stress recovery.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace contactqp::detail {

struct QuadraturePoint {
  double xi, eta, weight;  // on the reference triangle (0,0), (1,0), (0,1); weights sum to ½
};

// The centroid rule for order 1 (exact for a straight 3-node triangle's constant strain);
// Dunavant's 6-point degree-4 rule for order 2 (exact for straight 6-node triangles,
// accurate for curved ones). Returns the number of points; `points` stays valid.
int triangle_rule(int order, const QuadraturePoint*& points);

// N_i(ξ, η): 3 or 6 values. Node order: vertices 0, 1, 2, then mid-sides 01, 12, 20.
Eigen::VectorXd shape_values(int order, double xi, double eta);

// dN_i/dξ (row 0) and dN_i/dη (row 1).
Eigen::Matrix<double, 2, Eigen::Dynamic> shape_gradients(int order, double xi, double eta);

// Reference coordinates of node i of the element (vertices, then mid-sides).
Eigen::Vector2d reference_node(int i);

// An edge x(t) = Σ N_k(t) x_k, t ∈ [0, 1], through a, b (and the mid-side node m when
// quadratic): the shape values at t (a, b, m) and dx/dt.
struct EdgePoint {
  double N[3];
  Eigen::Vector3d dx;
};
EdgePoint edge_point(double t, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d* m);

// Gauss–Legendre on [0, 1], 3 points: exact up to degree 5.
extern const double kEdgeGaussT[3];
extern const double kEdgeGaussW[3];

struct TetrahedronPoint {
  double xi, eta, zeta, weight;  // on the reference tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1); weights sum to 1/6
};

// The centroid rule for order 1 (exact for a straight 4-node tetrahedron's constant strain);
// the symmetric 4-point degree-2 rule for order 2 (exact for the stiffness and the consistent
// body force of a straight 10-node tetrahedron). Returns the number of points.
int tetrahedron_rule(int order, const TetrahedronPoint*& points);

// N_i(ξ, η, ζ): 4 or 10 values. Node order: vertices 0–3, then mid-edges 01, 12, 20, 03, 13, 23.
Eigen::VectorXd tetrahedron_values(int order, double xi, double eta, double zeta);

// dN_i/dξ, dN_i/dη, dN_i/dζ (rows 0, 1, 2).
Eigen::Matrix<double, 3, Eigen::Dynamic> tetrahedron_gradients(int order, double xi, double eta, double zeta);

// Reference coordinates of node i of a tetrahedron (vertices, then mid-edges).
Eigen::Vector3d reference_tetrahedron_node(int i);

// The reference cell of a dimension — the triangle (dim 2) or the tetrahedron (dim 3) — behind
// one interface, for loops written once for both (body forces, stress recovery, the stiffness'
// quadrature): the functions above, with the point as a vector.
template <int dim>
using ReferencePoint = Eigen::Matrix<double, dim, 1>;

template <int dim>
struct CellPoint {
  ReferencePoint<dim> xi;
  double weight;  // the weights sum to the reference cell's measure (½, 1/6)
};

// triangle_rule / tetrahedron_rule.
template <int dim>
std::vector<CellPoint<dim>> cell_rule(int order);
// shape_values / tetrahedron_values.
template <int dim>
Eigen::VectorXd cell_values(int order, const ReferencePoint<dim>& xi);
// shape_gradients / tetrahedron_gradients: row r holds dN_i/dξ_r.
template <int dim>
Eigen::Matrix<double, dim, Eigen::Dynamic> cell_gradients(int order, const ReferencePoint<dim>& xi);
// reference_node / reference_tetrahedron_node.
template <int dim>
ReferencePoint<dim> cell_node(int i);

// Defined for dim 2 and 3 only (shape_functions.cpp).
template <>
std::vector<CellPoint<2>> cell_rule<2>(int order);
template <>
std::vector<CellPoint<3>> cell_rule<3>(int order);
template <>
Eigen::VectorXd cell_values<2>(int order, const Eigen::Vector2d& xi);
template <>
Eigen::VectorXd cell_values<3>(int order, const Eigen::Vector3d& xi);
template <>
Eigen::Matrix<double, 2, Eigen::Dynamic> cell_gradients<2>(int order, const Eigen::Vector2d& xi);
template <>
Eigen::Matrix<double, 3, Eigen::Dynamic> cell_gradients<3>(int order, const Eigen::Vector3d& xi);
template <>
Eigen::Vector2d cell_node<2>(int i);
template <>
Eigen::Vector3d cell_node<3>(int i);

}  // namespace contactqp::detail
