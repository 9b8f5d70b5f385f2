#include <algorithm>
#include <cmath>
#include <map>

#include "../contact/contact.hpp"
#include "contactqp/post.hpp"

namespace contactqp {
namespace {

// The direction from a circle's centre to its candidate with the smallest initial gap: the
// origin of the arc-length coordinate (decided by the initial gaps of the scene's own frame,
// so a rotated scene measures from the same node).
Eigen::Vector2d circle_origin(const Model& model, int obstacle) {
  const Candidate* closest = nullptr;
  for (const Candidate& candidate : model.candidates)
    if (candidate.obstacle == obstacle && (!closest || candidate.gap < closest->gap)) closest = &candidate;
  if (!closest) return Eigen::Vector2d::UnitY();
  const Eigen::Vector2d d = model.mesh.nodes[closest->node] - model.scene.obstacles[obstacle].center;
  return d.norm() > 0 ? Eigen::Vector2d(d.normalized()) : Eigen::Vector2d::UnitY();
}

// Force, centre and widths of one obstacle's profile (sorted by s).
// `axis`: the symmetry plane's direction (the scene's own y axis, turned by its transform).
void measure(ObstacleContact& contact, bool symmetry, const Eigen::Vector2d& axis, double thickness, double lambda_max) {
  // With symmetry the mirrored half adds the same push along the axis, the opposite across it.
  if (symmetry) contact.resultant = 2.0 * contact.resultant.dot(axis) * axis;
  const double loaded = 1e-8 * lambda_max;
  double sum = 0, first_moment = 0;
  for (const ContactProfilePoint& point : contact.profile) {
    sum += point.force;
    first_moment += point.force * point.s;
    if (point.force > loaded && lambda_max > 0) ++contact.contact_nodes;
    contact.max_pressure = std::max(contact.max_pressure, point.pressure);
  }
  contact.total_force = (symmetry ? 2.0 : 1.0) * sum;
  contact.line_load = contact.total_force / thickness;
  contact.centre = (symmetry || !(sum > 0)) ? 0.0 : first_moment / sum;
  if (!(sum > 0)) return;
  double second_moment = 0;
  for (const ContactProfilePoint& point : contact.profile) {
    const double d = point.s - contact.centre;
    second_moment += point.force * d * d;
    if (point.force > loaded) contact.half_width_last_node = std::max(contact.half_width_last_node, std::abs(d));
  }
  contact.half_width = 2.0 * std::sqrt(second_moment / sum);
}

// Boundary nodes that were not candidates must not have entered an obstacle.
void check_non_candidates(const Model& model, const Eigen::VectorXd& u, ContactSummary& summary) {
  const Eigen::VectorXd displacement = full_displacement(model, u);
  std::map<std::pair<int, int>, bool> is_candidate;
  for (const Candidate& candidate : model.candidates) is_candidate[{candidate.node, candidate.obstacle}] = true;
  const double tolerance = 1e-6 * std::max(displacement.size() ? displacement.cwiseAbs().maxCoeff() : 0.0, 1e-300);
  std::vector<int> nodes;
  for (const BoundaryEdge& edge : outer_boundary(model.mesh)) {
    nodes.push_back(edge.a);
    if (edge.mid >= 0) nodes.push_back(edge.mid);
  }
  for (int node : nodes) {
    const Eigen::Vector2d moved = model.mesh.nodes[node] + displacement.segment<2>(2 * node);
    for (size_t o = 0; o < model.scene.obstacles.size(); ++o) {
      if (is_candidate.count({node, static_cast<int>(o)})) continue;
      const double gap = detail::project(model.scene.obstacles[o], moved).gap;
      if (gap < -tolerance) {
        ++summary.penetrating_non_candidates;
        summary.max_non_candidate_penetration = std::max(summary.max_non_candidate_penetration, -gap);
      }
    }
  }
}

}  // namespace

ContactSummary summarize_contact(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& u,
                                 const Eigen::VectorXd& lambda) {
  ContactSummary summary;
  const double thickness = model.scene.body.thickness;
  const int n_obstacles = static_cast<int>(model.scene.obstacles.size());
  std::vector<Eigen::Vector2d> origins(n_obstacles, Eigen::Vector2d::UnitY());
  summary.obstacles.resize(n_obstacles);
  for (int o = 0; o < n_obstacles; ++o) {
    summary.obstacles[o].obstacle = o;
    if (model.scene.obstacles[o].type == "circle") origins[o] = circle_origin(model, o);
  }
  for (int i = 0; i < qp.n_constraints(); ++i) {
    const Candidate& candidate = model.candidates[i];
    const ObstacleSpec& obstacle = model.scene.obstacles[candidate.obstacle];
    ContactProfilePoint point;
    point.node = candidate.node;
    point.obstacle = candidate.obstacle;
    point.s = detail::surface_coordinate(obstacle, model.mesh.nodes[candidate.node], origins[candidate.obstacle]);
    point.force = lambda[i];
    point.pressure = candidate.tributary > 0 ? lambda[i] / (candidate.tributary * thickness) : 0.0;
    summary.obstacles[candidate.obstacle].profile.push_back(point);
    summary.obstacles[candidate.obstacle].resultant += lambda[i] * detail::project(obstacle, model.mesh.nodes[candidate.node]).normal;
  }
  const double lambda_max = lambda.size() ? lambda.maxCoeff() : 0.0;
  for (ObstacleContact& contact : summary.obstacles) {
    std::sort(contact.profile.begin(), contact.profile.end(),
              [](const ContactProfilePoint& a, const ContactProfilePoint& b) { return a.s < b.s; });
    measure(contact, model.scene.body.symmetry, model.rotation.col(1), thickness, lambda_max);
    summary.profile.insert(summary.profile.end(), contact.profile.begin(), contact.profile.end());
    summary.total_force += contact.total_force;
    summary.max_pressure = std::max(summary.max_pressure, contact.max_pressure);
    summary.contact_nodes += contact.contact_nodes;
    if (contact.total_force > summary.obstacles[summary.main_obstacle].total_force) summary.main_obstacle = contact.obstacle;
  }
  summary.line_load = summary.total_force / thickness;
  if (!summary.obstacles.empty()) {
    const ObstacleContact& main = summary.obstacles[summary.main_obstacle];
    summary.half_width = main.half_width;
    summary.half_width_last_node = main.half_width_last_node;
    summary.centre = main.centre;
  }
  check_non_candidates(model, u, summary);
  return summary;
}

}  // namespace contactqp
