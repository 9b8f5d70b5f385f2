// Shape functions and quadrature of the element types (3- and 6-node triangles, 4- and
// 10-node tetrahedra) and of their faces (edges in 2D, triangles in 3D), shared by the
// stiffness, the loads, the contact geometry and the stress recovery.
#pragma once

#include <Eigen/Core>

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

}  // namespace contactqp::detail
