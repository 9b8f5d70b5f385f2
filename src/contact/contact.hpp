// Contact: obstacle geometry, candidate selection and the rows of B u ≤ g.
#pragma once

#include <Eigen/Core>
#include <array>
#include <map>
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
// The same before the normals are made unit: sums over the boundary's faces, which a
// distributed mesh adds up over the ranks holding a node first (src/distributed/).
BoundaryNodeGeometry boundary_sums(const Mesh& mesh, const std::string& boundary);
void normalise_normals(BoundaryNodeGeometry& geometry);

// Nodes of the contact boundary that face an obstacle and whose initial gap is at most
// `max_gap`: one candidate per (node, obstacle). Facing: the boundary's outward normal at
// the node points against the obstacle normal at the closest point.
std::vector<Candidate> select_candidates(const Mesh& mesh, const std::vector<ObstacleSpec>& obstacles,
                                         const std::string& boundary, double max_gap);
// The same from the boundary's nodes as boundary_geometry() gives them.
std::vector<Candidate> select_candidates(const Mesh& mesh, const std::vector<ObstacleSpec>& obstacles,
                                         const BoundaryNodeGeometry& geometry, double max_gap);

// pair_rows.cpp: the point of a boundary face closest to p (initial or deformed positions x):
// its shape weights N_j (face node order), the face's outward unit normal there, the face's
// parameters (2D: t ∈ [0, 1] from a to b; 3D: (ξ, η) with weights 1 − ξ − η, ξ, η at the
// vertices) and the vertex it is (within 1e-9 of the parameters), or −1.
struct FaceProjection {
  Eigen::Vector3d point = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero();
  std::array<double, 6> weights{{0, 0, 0, 0, 0, 0}};
  Eigen::Vector2d parameters = Eigen::Vector2d::Zero();
  int n_nodes = 0;
  int vertex = -1;
  int face = -1;  // project_along_common_normal: the face, in its boundary
};
FaceProjection project_to_face(const std::vector<Eigen::Vector3d>& x, const BoundaryFace& face, int dim,
                               const Eigen::Vector3d& p);

// The face of `faces` closest to p, with its projection (face −1 when there are none).
struct ClosestFace {
  int face = -1;
  double distance = 0;
  FaceProjection projection;
};
ClosestFace closest_face(const std::vector<Eigen::Vector3d>& x, const std::vector<BoundaryFace>& faces, int dim,
                         const Eigen::Vector3d& p);

// The partner of node p (outward unit normal node_normal) on the other side's faces: where
// the line through p along the common normal d = (n_other − n_node)/|…| meets them, n_other
// interpolated from the other side's vertex normals at the meeting point, d and the point
// iterated to agreement from the closest point. For two surfaces that mirror each other
// (identical bodies) this is the mirror-image point, which the closest point is not: the
// pairing, and with it the pressure, is then the same seen from either side. nullopt when the
// line meets no face near the closest point.
std::optional<FaceProjection> project_along_common_normal(const Mesh& mesh, const std::vector<BoundaryFace>& faces,
                                                          const std::map<int, Eigen::Vector3d>& vertex_normal,
                                                          const Eigen::Vector3d& p, const Eigen::Vector3d& node_normal,
                                                          const ClosestFace& closest);

// The smallest face of a boundary: its length in 2D, its mean edge length in 3D.
double smallest_face_size(const Mesh& mesh, const std::string& boundary);

// The nodes of `node_boundary` against the faces of `face_boundary` (of another body, in the
// same mesh): one candidate per node whose closest point faces it within max_gap. A closest
// point at a vertex uses the face boundary's averaged normal there. Sets node, gap, tributary,
// face, face_nodes, weights and normal; the caller sets pair and the bodies.
std::vector<Candidate> select_pair_candidates(const Mesh& mesh, const std::string& node_boundary,
                                              const std::string& face_boundary, double max_gap);

// mortar_rows.cpp: the pair's rows as mortar rows (ContactPair::rows, docs/bodies.md): each
// candidate node of `node_boundary` gets the weights M_ij / D_i over the faces of
// `face_boundary` that its share of its side overlaps, the mean normal there, the gap of its
// node against that weighted partner, and D_i = ∫N_i over the side's linear pieces as its
// tributary. A node whose share reaches beyond the other side keeps its node-to-face row.
void make_mortar_rows(const Mesh& mesh, const std::string& node_boundary, const std::string& face_boundary,
                      std::vector<Candidate>& candidates);

// Drops candidates with no free DOF along the obstacle normal (their position is prescribed):
// they add no unknown. InputError when such a prescribed position penetrates the obstacle.
void remove_prescribed_candidates(Model& model);

// The row of one candidate: its coefficients on the free DOFs (model.free_index), and g with
// the prescribed part moved in. An obstacle's row has the node's own DOFs only.
struct ContactRowEntries {
  std::vector<std::pair<int, double>> coefficients;  // (free column, −n_c)
  double g = 0;
};
ContactRowEntries contact_row(const Model& model, const Candidate& candidate);

// friction_rows.cpp: friction (friction.hpp, docs/friction.md).
// The friction section that applies to a candidate's row, or nullptr (frictionless).
const FrictionSpec* friction_of(const Model& model, const Candidate& candidate);
// The frame of a row's friction: its unit normal (from the obstacle or the other body towards
// the node, global axes; a pair's common normal, Candidate::common_normal) and its dim − 1
// unit tangents: t = (n_y, −n_x) in 2D; in 3D t1 the scene's own x axis
// (its y axis where n lies near x) across n, and t2 = n × t1. At a node with a prescribed
// direction within 0.1 of the plane across n (a symmetry plane's normal) that direction is a
// tangent (t2 in 3D, t1 = t2 × n normalised), so that its row vanishes once the prescribed
// DOFs are eliminated; it leans off n's plane by the mesh normal's error only.
Eigen::Vector3d row_normal(const Model& model, const Candidate& candidate);
std::vector<Eigen::Vector3d> row_tangents(const Model& model, const Candidate& candidate);
// The tangential rows over every DOF (free and prescribed), in the DOFs' frames: row
// i·(dim − 1) + k is t_kᵀ(u_i − Σ_j N_j u_j) for candidate i.
struct TangentialRow {
  std::vector<std::pair<int, double>> entries;  // (DOF, coefficient)
};
std::vector<TangentialRow> tangential_rows(const Model& model);
// Each tangential row's position for the free DOFs u and the model's prescribed values.
Eigen::VectorXd tangential_positions(const Model& model, const Eigen::VectorXd& u);
// qp.friction.offset = previous − (the prescribed values' part of each row): T u − offset is
// then the slip since `previous` (the positions at the end of the last step).
void set_friction_offset(const Model& model, QuadraticProgram& qp, const Eigen::VectorXd& previous);
// Fills qp.friction (T, the bounds, the offset of a first step) when the scene has friction;
// leaves it empty otherwise.
void add_friction_rows(const Model& model, QuadraticProgram& qp);

// One row of B and entry of g per candidate, in candidate order: −nᵀ u_i ≤ g_i (n of length
// dim), u_i in the node's DOF frame, with the prescribed components of u_i moved into g.
void add_contact_rows(const Model& model, QuadraticProgram& qp);

}  // namespace contactqp::detail
