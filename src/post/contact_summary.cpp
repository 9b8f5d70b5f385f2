#include <algorithm>
#include <cmath>
#include <map>

#include "../contact/contact.hpp"
#include "contactqp/post.hpp"

namespace contactqp {
namespace {

// Coordinate along a plane obstacle, measured from the foot of the body's axis: for the half
// disc the axis passes through its centre (0, R).
double along_surface(const Model& model, const ObstacleSpec& obstacle, const Eigen::Vector2d& x) {
  const Eigen::Vector2d tangent(obstacle.normal.y(), -obstacle.normal.x());
  const Eigen::Vector2d axis(0.0, model.scene.body.radius);
  return (x - axis).dot(tangent);
}

}  // namespace

ContactSummary summarize_contact(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& u,
                                 const Eigen::VectorXd& lambda) {
  ContactSummary summary;
  const double thickness = model.scene.body.thickness;
  const double mirror = model.scene.body.symmetry ? 2.0 : 1.0;
  const double lambda_max = lambda.size() ? lambda.maxCoeff() : 0.0;
  const double loaded = 1e-8 * lambda_max;

  double sum = 0, first_moment = 0;
  for (int i = 0; i < qp.n_constraints(); ++i) {
    const Candidate& candidate = model.candidates[i];
    const ObstacleSpec& obstacle = model.scene.obstacles[candidate.obstacle];
    ContactProfilePoint point;
    point.node = candidate.node;
    point.s = along_surface(model, obstacle, model.mesh.nodes[candidate.node]);
    point.force = lambda[i];
    point.pressure = candidate.tributary > 0 ? lambda[i] / (candidate.tributary * thickness) : 0.0;
    summary.profile.push_back(point);
    sum += lambda[i];
    first_moment += lambda[i] * point.s;
    if (lambda[i] > loaded && lambda_max > 0) ++summary.contact_nodes;
    summary.max_pressure = std::max(summary.max_pressure, point.pressure);
  }
  std::sort(summary.profile.begin(), summary.profile.end(),
            [](const ContactProfilePoint& a, const ContactProfilePoint& b) { return a.s < b.s; });
  summary.total_force = mirror * sum;
  summary.line_load = summary.total_force / thickness;
  summary.centre = (model.scene.body.symmetry || !(sum > 0)) ? 0.0 : first_moment / sum;
  if (sum > 0) {
    double second_moment = 0;
    for (const ContactProfilePoint& point : summary.profile) {
      const double d = point.s - summary.centre;
      second_moment += point.force * d * d;
      if (point.force > loaded) summary.half_width_last_node = std::max(summary.half_width_last_node, std::abs(d));
    }
    summary.half_width = 2.0 * std::sqrt(second_moment / sum);
  }

  // Boundary nodes that were not candidates must not have entered an obstacle.
  const Eigen::VectorXd displacement = full_displacement(model, u);
  std::map<std::pair<int, int>, bool> is_candidate;
  for (const Candidate& candidate : model.candidates) is_candidate[{candidate.node, candidate.obstacle}] = true;
  const double tolerance = 1e-6 * std::max(displacement.size() ? displacement.cwiseAbs().maxCoeff() : 0.0, 1e-300);
  for (const auto& [name, edges] : model.mesh.boundaries) {
    for (int node : boundary_nodes(model.mesh, name)) {
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
  return summary;
}

}  // namespace contactqp
