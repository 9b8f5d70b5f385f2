#include "adaptive_warm_start.hpp"

#include <algorithm>
#include <cmath>

#include "contactqp/post.hpp"

namespace contactqp::detail {

WarmStart::WarmStart(const Model& model, const QuadraticProgram& qp, const SolveResult& result)
    : dim_(model.dim), global_frames_(model.frame_of_node.empty()) {
  const Mesh& mesh = model.mesh;
  const Eigen::VectorXd full = full_displacement(model, result.u);
  // The pressure at each row's node, and at the face nodes of a pair's row too: the next mesh
  // may put the pair's nodes on the other side.
  std::vector<double> node_pressure(mesh.n_nodes(), 0.0);
  if (result.lambda.size() == qp.n_constraints() && qp.n_constraints() > 0) {
    const std::vector<double> p = nodal_pressures(model, qp, result.lambda);
    for (std::size_t i = 0; i < model.candidates.size() && i < p.size(); ++i) {
      const Candidate& row = model.candidates[i];
      const double value = std::isfinite(p[i]) ? std::max(0.0, p[i]) : 0.0;
      node_pressure[row.node] = std::max(node_pressure[row.node], value);
      for (int k = 0; k < row.n_face_nodes; ++k)
        if (row.weights[k] > 0) node_pressure[row.face_nodes[k]] = std::max(node_pressure[row.face_nodes[k]], value);
    }
  }
  const int n_bodies = std::max<int>(1, static_cast<int>(model.bodies.size()));
  for (int b = 0; b < n_bodies; ++b) {
    const bool several = !model.bodies.empty();
    const int first = several ? model.bodies[b].first_element : 0;
    const int count = several ? model.bodies[b].n_elements : mesh.n_elements();
    std::vector<int> vertex_of(mesh.n_nodes(), -1);
    std::vector<Eigen::Vector3d> vertices;
    std::vector<std::array<int, 4>> simplices;
    Body body;
    body.displacement.resize(dim_);
    for (int e = first; e < first + count; ++e) {
      const int* v = mesh.element(e);
      std::array<int, 4> simplex{0, 0, 0, 0};
      for (int k = 0; k <= dim_; ++k) {
        int& local = vertex_of[v[k]];
        if (local < 0) {
          local = static_cast<int>(vertices.size());
          vertices.push_back(mesh.nodes[v[k]]);
          for (int c = 0; c < dim_; ++c) body.displacement[c].push_back(full[dim_ * v[k] + c]);
          body.pressure.push_back(node_pressure[v[k]]);
        }
        simplex[k] = local;
      }
      simplices.push_back(simplex);
    }
    body.locator = std::make_shared<const PointLocator>(dim_, std::move(vertices), std::move(simplices));
    bodies_.push_back(std::move(body));
  }
  for (const RigidSurface& surface : model.rigid_surfaces)
    rigid_surface_values_.push_back(surface.column < result.u.size() ? result.u[surface.column] : 0.0);
  for (const RigidRotation& turn : model.rigid_rotations)
    rigid_surface_values_.push_back(turn.column < result.u.size() ? result.u[turn.column] : 0.0);
}

InitialGuess WarmStart::operator()(const Model& model, const QuadraticProgram& qp) const {
  InitialGuess guess;
  if (model.dim != dim_) return guess;
  const auto body_of = [&](int node) {
    return std::clamp(model.body_of_node(node), 0, static_cast<int>(bodies_.size()) - 1);
  };
  if (global_frames_ && model.frame_of_node.empty() &&
      model.rigid_surfaces.size() + model.rigid_rotations.size() == rigid_surface_values_.size()) {
    guess.u = Eigen::VectorXd::Zero(qp.n_dofs());
    for (int n = 0; n < model.mesh.n_nodes(); ++n) {
      const Body& body = bodies_[body_of(n)];
      const PointLocator::Location at = body.locator->locate(model.mesh.nodes[n]);
      for (int c = 0; c < dim_; ++c) {
        const int index = model.free_index[dim_ * n + c];
        if (index >= 0 && index < guess.u.size()) guess.u[index] = body.locator->interpolate(at, body.displacement[c]);
      }
    }
    for (std::size_t s = 0; s < model.rigid_surfaces.size(); ++s) {
      const int column = model.rigid_surfaces[s].column;
      if (column >= 0 && column < guess.u.size()) guess.u[column] = rigid_surface_values_[s];
    }
    for (std::size_t r = 0; r < model.rigid_rotations.size(); ++r) {  // a turning surface's angles
      const int column = model.rigid_rotations[r].column;
      if (column < guess.u.size()) guess.u[column] = rigid_surface_values_[model.rigid_surfaces.size() + r];
    }
  }
  // λ_i = p(x_i) / (the pressure of a unit λ_i): the row's tributary (and thickness) as
  // nodal_pressures() divides by them.
  const int m = qp.n_constraints();
  if (m > 0 && static_cast<int>(model.candidates.size()) == m) {
    const std::vector<double> unit = nodal_pressures(model, qp, Eigen::VectorXd::Ones(m));
    guess.lambda = Eigen::VectorXd::Zero(m);
    for (int i = 0; i < m; ++i) {
      const int node = model.candidates[i].node;
      const Body& body = bodies_[body_of(node)];
      const double p = body.locator->interpolate(model.mesh.nodes[node], body.pressure);
      if (p > 0 && unit[i] > 0 && std::isfinite(unit[i])) guess.lambda[i] = p / unit[i];
    }
  }
  return guess;
}

}  // namespace contactqp::detail
