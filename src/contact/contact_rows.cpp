#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <map>

#include "contact.hpp"
#include "contactqp/errors.hpp"
#include "mesh/shape_functions.hpp"

namespace contactqp::detail {

namespace {

// Per node: the sum of the unit normals of its faces and its tributary length or area.
using NodeSums = std::map<int, std::pair<Eigen::Vector3d, double>>;

void add_to(NodeSums& per_node, int node, const Eigen::Vector3d& normal, double w) {
  auto& entry = per_node.try_emplace(node, Eigen::Vector3d::Zero(), 0.0).first->second;
  entry.first += normal;
  entry.second += w;
}

// A 2D edge: ∫ N_i |x'(t)| dt by three Gauss points (exact for the polynomial part on a
// straight quadratic edge, accurate on a curved one); the normal of the chord a → b.
void add_edge(const Mesh& mesh, const BoundaryFace& edge, NodeSums& per_node) {
  const Eigen::Vector3d& a = mesh.nodes[edge.nodes[0]];
  const Eigen::Vector3d& b = mesh.nodes[edge.nodes[1]];
  const bool quadratic = edge.n_nodes == 3;
  double w_a = 0, w_b = 0, w_m = 0;
  for (int q = 0; q < 3; ++q) {
    const EdgePoint p = edge_point(kEdgeGaussT[q], a, b, quadratic ? &mesh.nodes[edge.nodes[2]] : nullptr);
    const double jacobian = p.dx.norm() * kEdgeGaussW[q];
    w_a += p.N[0] * jacobian;
    w_b += p.N[1] * jacobian;
    w_m += p.N[2] * jacobian;
  }
  const Eigen::Vector3d tangent = b - a;
  const Eigen::Vector3d normal = Eigen::Vector3d(tangent.y(), -tangent.x(), 0.0).normalized();  // body on the left
  add_to(per_node, edge.nodes[0], normal, w_a);
  add_to(per_node, edge.nodes[1], normal, w_b);
  if (quadratic) add_to(per_node, edge.nodes[2], normal, w_m);
}

double triangle_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return 0.5 * (b - a).cross(c - a).norm();
}

// A 3D face: a third of a linear face's area to each vertex (= ∫ N_i dA). A 6-node face gives
// its consistent weights too, ∫ N_i dA: 0 at its vertices and a third of its area (the sum of
// its four 3-node sub-triangles at the mid-sides) to each mid-side node. The contact forces
// follow these weights — a 10-node body's vertices carry almost none (docs/scenes.md,
// "Tributary areas") — so the pressure at a vertex is taken from its mid-sides instead
// (nodal_pressures in post.hpp).
void add_face(const Mesh& mesh, const BoundaryFace& face, NodeSums& per_node) {
  const Eigen::Vector3d normal = face_normal(mesh, face);
  const auto& x = mesh.nodes;
  const auto& v = face.nodes;
  if (face.n_nodes == 3) {
    const double third = triangle_area(x[v[0]], x[v[1]], x[v[2]]) / 3.0;
    for (int k = 0; k < 3; ++k) add_to(per_node, v[k], normal, third);
    return;
  }
  const int sub[4][3] = {{v[0], v[3], v[5]}, {v[1], v[4], v[3]}, {v[2], v[5], v[4]}, {v[3], v[4], v[5]}};
  double area = 0;
  for (const auto& t : sub) area += triangle_area(x[t[0]], x[t[1]], x[t[2]]);
  for (int k = 0; k < 3; ++k) add_to(per_node, v[k], normal, 0.0);
  for (int k = 3; k < 6; ++k) add_to(per_node, v[k], normal, area / 3.0);
}

}  // namespace

BoundaryNodeGeometry boundary_sums(const Mesh& mesh, const std::string& boundary) {
  NodeSums per_node;  // node -> (normal sum, tributary)
  auto it = mesh.boundaries.find(boundary);
  if (it != mesh.boundaries.end()) {
    for (const BoundaryFace& face : it->second) {
      if (mesh.dim == 2)
        add_edge(mesh, face, per_node);
      else
        add_face(mesh, face, per_node);
    }
  }
  BoundaryNodeGeometry geometry;
  for (const auto& [node, entry] : per_node) {
    geometry.nodes.push_back(node);
    geometry.normals.push_back(entry.first);
    geometry.tributary.push_back(entry.second);
  }
  return geometry;
}

void normalise_normals(BoundaryNodeGeometry& geometry) {
  for (Eigen::Vector3d& n : geometry.normals)
    if (n.norm() > 0) n.normalize();
}

BoundaryNodeGeometry boundary_geometry(const Mesh& mesh, const std::string& boundary) {
  BoundaryNodeGeometry geometry = boundary_sums(mesh, boundary);
  normalise_normals(geometry);
  return geometry;
}

std::vector<Candidate> select_candidates(const Mesh& mesh, const std::vector<ObstacleSpec>& obstacles,
                                         const std::string& boundary, double max_gap) {
  return select_candidates(mesh, obstacles, boundary_geometry(mesh, boundary), max_gap);
}

std::vector<Candidate> select_candidates(const Mesh& mesh, const std::vector<ObstacleSpec>& obstacles,
                                         const BoundaryNodeGeometry& geometry, double max_gap) {
  std::vector<Candidate> candidates;
  for (size_t k = 0; k < geometry.nodes.size(); ++k) {
    const int node = geometry.nodes[k];
    for (size_t o = 0; o < obstacles.size(); ++o) {
      const ObstacleProjection projection = project(obstacles[o], mesh.nodes[node]);
      // Facing: the body's outward normal points against the obstacle normal. A small
      // tolerance keeps the tangent points at the ends of an arc out.
      const bool facing = geometry.normals[k].dot(projection.normal) < -1e-9;
      if (facing && projection.gap <= max_gap) {
        Candidate candidate;
        candidate.node = node;
        candidate.obstacle = static_cast<int>(o);
        candidate.gap = projection.gap;
        candidate.tributary = geometry.tributary[k];
        candidates.push_back(candidate);
      }
    }
  }
  return candidates;
}

namespace {

// A row between two bodies: −nᵀ u_i + Σ_j N_j nᵀ u_j ≤ g (no DOF frames: a scene with bodies
// has no transform).
ContactRowEntries pair_row_of(const Model& model, const Candidate& candidate) {
  ContactRowEntries row;
  row.g = candidate.gap;
  const int dim = model.dim;
  auto add = [&](int node, double scale) {
    for (int c = 0; c < dim; ++c) {
      const int dof = dim * node + c;
      const double value = scale * candidate.normal[c];
      if (value == 0.0) continue;
      if (model.free_index[dof] < 0) row.g -= value * model.prescribed[dof];
      for_each_column(model, dof, [&](int column, double w) { row.coefficients.emplace_back(column, w * value); });
    }
  };
  add(candidate.node, -1.0);
  for (int j = 0; j < candidate.n_face_nodes; ++j)
    if (candidate.weights[j] != 0.0) add(candidate.face_nodes[j], candidate.weights[j]);
  return row;
}

}  // namespace

ContactRowEntries contact_row(const Model& model, const Candidate& candidate) {
  if (candidate.pair >= 0) return pair_row_of(model, candidate);
  const ObstacleProjection projection =
      project(model.scene.obstacles[candidate.obstacle], model.mesh.nodes[candidate.node]);
  ContactRowEntries row;
  row.g = projection.gap;
  // −nᵀu_i with u_i = T a_i (T the node's DOF frame): the coefficients of a_i are −Tᵀn.
  const int dim = model.dim;
  Eigen::VectorXd n = projection.normal.head(dim);
  if (!model.frame_of_node.empty() && model.frame_of_node[candidate.node] >= 0)
    n = dof_frame(model, candidate.node).transpose() * n;
  for (int c = 0; c < dim; ++c) {
    const int dof = dim * candidate.node + c;
    const int column = model.free_index[dof];
    // A component that is zero but for round-off (a normal along a rotated DOF axis) is zero:
    // the same scene turned by any angle then gives the same rows.
    const double n_c = std::abs(n[c]) < 1e-14 ? 0.0 : n[c];
    if (column < 0)
      row.g += n_c * model.prescribed[dof];  // −n_c u_c is known: move it to the right-hand side
    else if (n_c != 0.0)
      for_each_column(model, dof, [&](int col, double w) { row.coefficients.emplace_back(col, -w * n_c); });
  }
  return row;
}

void remove_prescribed_candidates(Model& model) {
  std::vector<Candidate> kept;
  for (const Candidate& candidate : model.candidates) {
    const ContactRowEntries row = contact_row(model, candidate);
    if (!row.coefficients.empty()) {
      kept.push_back(candidate);
      continue;
    }
    // Nothing to solve for at this node; its prescribed position must not be inside the obstacle.
    if (row.g < -1e-12 * std::max(1e-300, std::abs(candidate.gap) + model.prescribed.cwiseAbs().maxCoeff()) &&
        candidate.pair >= 0)
      throw InputError(model.scene.pairs[candidate.pair].path,
                       "prescribes node " + std::to_string(candidate.node) + " at " +
                           format_point(model.mesh.nodes[candidate.node], model.dim) + " " + format_value(-row.g) +
                           " deep into the other body");
    if (row.g < -1e-12 * std::max(1e-300, std::abs(candidate.gap) + model.prescribed.cwiseAbs().maxCoeff()))
      throw InputError("load", "prescribes node " + std::to_string(candidate.node) + " at " +
                                   format_point(model.mesh.nodes[candidate.node], model.dim) + " " +
                                   format_value(-row.g) + " deep into obstacle " + std::to_string(candidate.obstacle));
  }
  model.candidates = std::move(kept);
}

void add_contact_rows(const Model& model, QuadraticProgram& qp) {
  const int m = static_cast<int>(model.candidates.size());
  std::vector<Eigen::Triplet<double>> entries;
  qp.g.resize(m);
  qp.rows.resize(m);
  for (int i = 0; i < m; ++i) {
    const Candidate& candidate = model.candidates[i];
    const ContactRowEntries row = contact_row(model, candidate);
    for (const auto& [column, value] : row.coefficients) entries.emplace_back(i, column, value);
    qp.g[i] = row.g;
    qp.rows[i] = {candidate.node, candidate.obstacle, candidate.pair};
  }
  qp.B.resize(m, qp.n_dofs());
  qp.B.setFromTriplets(entries.begin(), entries.end());
  qp.B.makeCompressed();
}

}  // namespace contactqp::detail
