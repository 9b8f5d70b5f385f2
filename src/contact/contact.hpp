// Contact: obstacle geometry, candidate selection and the rows of B u ≤ g.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "contactqp/model.hpp"

namespace contactqp::detail {

// A point's initial gap to an obstacle, measured along the obstacle normal at the closest
// point, and that normal (unit, from the obstacle towards the body). For a profile whose
// closest point is a vertex, the normal points from the vertex to the point; the gap is
// signed by the side of the vertex's pseudo-normal (negative inside the obstacle).
// Points and normals are 3-vectors (z = 0 in 2D). A punch's rim is a sharp edge: past it the
// normal points from the rim to x.
struct ObstacleProjection {
  double gap = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();
};
ObstacleProjection project(const ObstacleSpec& obstacle, const Eigen::Vector3d& x);
ObstacleProjection project(const ObstacleSpec& obstacle, const Eigen::Vector2d& x);  // 2D: (x, y, 0)

// 2D: the position of x's closest point along the obstacle surface (length): a plane from its
// `point` along t = (n_y, −n_x); a circle by arc length from the direction `origin` (unit,
// from the centre), increasing along t; a profile by arc length from its first point.
double surface_coordinate(const ObstacleSpec& obstacle, const Eigen::Vector3d& x, const Eigen::Vector3d& origin);
double surface_coordinate(const ObstacleSpec& obstacle, const Eigen::Vector2d& x, const Eigen::Vector2d& origin);

// Curvature of the obstacle's surface seen from the body, when it is the same in every
// direction: 1/r for a circle or a sphere, 0 for a plane or a punch's face; 0 for a profile
// (piecewise flat); nullopt for a cylinder (curved one way only).
std::optional<double> obstacle_curvature(const ObstacleSpec& obstacle);

// Outward unit normal of a boundary at each of its nodes (average of its faces' normals),
// and the node's tributary length (2D: ∫ N_i ds) or area (3D: see Candidate::tributary) —
// keyed by node index.
struct BoundaryNodeGeometry {
  std::vector<int> nodes;
  std::vector<Eigen::Vector3d> normals;
  std::vector<double> tributary;
};
BoundaryNodeGeometry boundary_geometry(const Mesh& mesh, const std::string& boundary);

// Nodes of the contact boundary that face an obstacle and whose initial gap is at most
// `max_gap`: one candidate per (node, obstacle). Facing: the boundary's outward normal at
// the node points against the obstacle normal at the closest point.
std::vector<Candidate> select_candidates(const Mesh& mesh, const std::vector<ObstacleSpec>& obstacles,
                                         const std::string& boundary, double max_gap);

// Drops candidates with no free DOF along the obstacle normal (their position is prescribed):
// they add no unknown. InputError when such a prescribed position penetrates the obstacle.
void remove_prescribed_candidates(Model& model);

// One row of B and entry of g per candidate, in candidate order: −nᵀ u_i ≤ g_i (n of length
// dim), u_i in the node's DOF frame, with the prescribed components of u_i moved into g.
void add_contact_rows(const Model& model, QuadraticProgram& qp);

}  // namespace contactqp::detail
