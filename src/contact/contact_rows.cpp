#include <cmath>
#include <limits>
#include <map>

#include "contact.hpp"
#include "../fe/shape_functions.hpp"
#include "contactqp/errors.hpp"

namespace contactqp::detail {

BoundaryNodeGeometry boundary_geometry(const Mesh& mesh, const std::string& boundary) {
  std::map<int, std::pair<Eigen::Vector2d, double>> per_node;  // node -> (normal sum, tributary)
  auto it = mesh.boundaries.find(boundary);
  if (it != mesh.boundaries.end()) {
    for (const BoundaryEdge& edge : it->second) {
      const Eigen::Vector2d& a = mesh.nodes[edge.a];
      const Eigen::Vector2d& b = mesh.nodes[edge.b];
      // Edge x(t) = N_a a + N_b b (+ N_m m): linear, or quadratic through the mid-side node.
      // Three Gauss points: exact for the polynomial part of ∫ N_i |x'(t)| dt on a straight
      // quadratic edge, accurate on a curved one.
      const bool quadratic = edge.mid >= 0;
      double w_a = 0, w_b = 0, w_m = 0;
      for (int q = 0; q < 3; ++q) {
        const EdgePoint p = edge_point(kEdgeGaussT[q], a, b, quadratic ? &mesh.nodes[edge.mid] : nullptr);
        const double jacobian = p.dx.norm() * kEdgeGaussW[q];
        w_a += p.N[0] * jacobian;
        w_b += p.N[1] * jacobian;
        w_m += p.N[2] * jacobian;
      }
      const Eigen::Vector2d tangent = b - a;
      const Eigen::Vector2d normal = Eigen::Vector2d(tangent.y(), -tangent.x()).normalized();  // body on the left
      auto add = [&](int node, double w) {
        auto& entry = per_node.try_emplace(node, Eigen::Vector2d::Zero(), 0.0).first->second;
        entry.first += normal;
        entry.second += w;
      };
      add(edge.a, w_a);
      add(edge.b, w_b);
      if (quadratic) add(edge.mid, w_m);
    }
  }
  BoundaryNodeGeometry geometry;
  for (const auto& [node, entry] : per_node) {
    geometry.nodes.push_back(node);
    geometry.normals.push_back(entry.first.norm() > 0 ? Eigen::Vector2d(entry.first.normalized()) : entry.first);
    geometry.tributary.push_back(entry.second);
  }
  return geometry;
}

std::vector<Candidate> select_candidates(const Mesh& mesh, const std::vector<ObstacleSpec>& obstacles,
                                         const std::string& boundary, double max_gap) {
  const BoundaryNodeGeometry geometry = boundary_geometry(mesh, boundary);
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

// The row of one candidate: coefficients on free DOFs, and g with the prescribed part moved in.
struct ContactRowEntries {
  std::vector<std::pair<int, double>> coefficients;  // (free column, −n_c)
  double g = 0;
};

ContactRowEntries row_of(const Model& model, const Candidate& candidate) {
  const ObstacleProjection projection =
      project(model.scene.obstacles[candidate.obstacle], model.mesh.nodes[candidate.node]);
  ContactRowEntries row;
  row.g = projection.gap;
  // −nᵀu_i with u_i = T a_i (T the node's DOF frame): the coefficients of a_i are −Tᵀn.
  const Eigen::Vector2d n = dof_frame(model, candidate.node).transpose() * projection.normal;
  for (int c = 0; c < 2; ++c) {
    const int dof = 2 * candidate.node + c;
    const int column = model.free_index[dof];
    // A component that is zero but for round-off (a normal along a rotated DOF axis) is zero:
    // the same scene turned by any angle then gives the same rows.
    const double n_c = std::abs(n[c]) < 1e-14 ? 0.0 : n[c];
    if (column < 0)
      row.g += n_c * model.prescribed[dof];  // −n_c u_c is known: move it to the right-hand side
    else if (n_c != 0.0)
      row.coefficients.emplace_back(column, -n_c);
  }
  return row;
}

}  // namespace

void remove_prescribed_candidates(Model& model) {
  std::vector<Candidate> kept;
  for (const Candidate& candidate : model.candidates) {
    const ContactRowEntries row = row_of(model, candidate);
    if (!row.coefficients.empty()) {
      kept.push_back(candidate);
      continue;
    }
    // Nothing to solve for at this node; its prescribed position must not be inside the obstacle.
    if (row.g < -1e-12 * std::max(1e-300, std::abs(candidate.gap) + model.prescribed.cwiseAbs().maxCoeff()))
      throw InputError("load", "prescribes node " + std::to_string(candidate.node) + " at (" +
                                   detail::format_value(model.mesh.nodes[candidate.node].x()) + ", " +
                                   detail::format_value(model.mesh.nodes[candidate.node].y()) + ") " +
                                   detail::format_value(-row.g) + " deep into obstacle " +
                                   std::to_string(candidate.obstacle));
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
    const ContactRowEntries row = row_of(model, candidate);
    for (const auto& [column, value] : row.coefficients) entries.emplace_back(i, column, value);
    qp.g[i] = row.g;
    qp.rows[i] = {candidate.node, candidate.obstacle};
  }
  qp.B.resize(m, qp.n_dofs());
  qp.B.setFromTriplets(entries.begin(), entries.end());
  qp.B.makeCompressed();
}

}  // namespace contactqp::detail
