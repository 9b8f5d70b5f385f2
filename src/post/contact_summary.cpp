#include <algorithm>
#include <cmath>
#include <map>

#include "contact/contact.hpp"
#include "contactqp/post.hpp"

namespace contactqp {
namespace {

// The direction from a circle's centre to its candidate with the smallest initial gap: the
// origin of the arc-length coordinate (decided by the initial gaps of the scene's own frame,
// so a rotated scene measures from the same node).
Eigen::Vector3d circle_origin(const Model& model, int obstacle) {
  const Candidate* closest = nullptr;
  for (const Candidate& candidate : model.candidates)
    if (candidate.obstacle == obstacle && (!closest || candidate.gap < closest->gap)) closest = &candidate;
  if (!closest) return Eigen::Vector3d::UnitY();
  const Eigen::Vector3d d =
      model.mesh.nodes[closest->node] - model.scene.obstacles[obstacle].as<CircleObstacle>()->center;
  return d.norm() > 0 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d::UnitY();
}

// Force, centre and widths of one obstacle's profile (sorted by s).
// `axis`: the symmetry plane's direction (the scene's own y axis, turned by its transform).
void measure(ObstacleContact& contact, bool symmetry, const Eigen::Vector3d& axis, double thickness,
             double lambda_max) {
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

// The 3D zone on one obstacle: the centre of pressure (on the symmetry axis with symmetry),
// each point's distance r from it across the obstacle normal there, the moment estimate of
// the contact radius, the loaded area. `points` are the candidates' initial positions.
void measure_3d(const Model& model, ObstacleContact& contact, const std::vector<Eigen::Vector3d>& points,
                const std::vector<double>& tributary, double lambda_max) {
  const double copies = mirror_copies(model);
  // With symmetry the mirrored parts' resultants add along the cuts and cancel across them.
  contact.resultant = whole_body_sum(model, contact.resultant);
  const double loaded = 1e-8 * lambda_max;
  double sum = 0;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < contact.profile.size(); ++k) {
    const ContactProfilePoint& point = contact.profile[k];
    sum += point.force;
    first_moment += point.force * points[k];
    if (point.force > loaded && lambda_max > 0) {
      ++contact.contact_nodes;
      contact.contact_area += copies * tributary[k];
    }
    contact.max_pressure = std::max(contact.max_pressure, point.pressure);
  }
  contact.total_force = copies * sum;
  contact.line_load = contact.total_force;
  if (!(sum > 0)) return;
  Eigen::Vector3d centre = first_moment / sum;
  centre = mirror_mean(model, centre);
  contact.centre_point = centre;
  const Eigen::Vector3d n = detail::project(model.scene.obstacles[contact.obstacle], centre).normal;
  double second_moment = 0;
  for (size_t k = 0; k < contact.profile.size(); ++k) {
    ContactProfilePoint& point = contact.profile[k];
    const Eigen::Vector3d d = points[k] - centre;
    point.s = (d - d.dot(n) * n).norm();
    second_moment += point.force * point.s * point.s;
    if (point.force > loaded) contact.contact_radius_last_node = std::max(contact.contact_radius_last_node, point.s);
  }
  contact.contact_radius = std::sqrt(2.5 * second_moment / sum);
}

}  // namespace

// Boundary nodes that were not candidates must not have entered an obstacle.
void check_non_candidates(const Model& model, const Eigen::VectorXd& u, ContactSummary& summary) {
  const Eigen::VectorXd displacement = full_displacement(model, u);
  const double tolerance = 1e-6 * std::max(displacement.size() ? displacement.cwiseAbs().maxCoeff() : 0.0, 1e-300);
  const int dim = model.dim;
  std::vector<int> nodes;
  if (dim == 2) {
    // Each vertex of the closed boundary is the first node of one edge.
    for (const BoundaryFace& edge : outer_boundary(model.mesh)) {
      nodes.push_back(edge.nodes[0]);
      if (edge.n_nodes == 3) nodes.push_back(edge.nodes[2]);
    }
  } else {
    std::vector<bool> seen(model.mesh.n_nodes(), false);
    for (const BoundaryFace& face : outer_boundary(model.mesh))
      for (int k = 0; k < face.n_nodes; ++k)
        if (!seen[face.nodes[k]]) {
          seen[face.nodes[k]] = true;
          nodes.push_back(face.nodes[k]);
        }
  }
  count_penetrating(model, displacement, nodes, tolerance, summary);
}

void count_penetrating(const Model& model, const Eigen::VectorXd& displacement, const std::vector<int>& nodes,
                       double tolerance, ContactSummary& summary) {
  std::map<std::pair<int, int>, bool> is_candidate;
  for (const Candidate& candidate : model.candidates) is_candidate[{candidate.node, candidate.obstacle}] = true;
  const int dim = model.dim;
  for (int node : nodes) {
    Eigen::Vector3d moved = model.mesh.nodes[node];
    moved.head(dim) += displacement.segment(dim * node, dim);
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

ContactSummary summarize_contact(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& u,
                                 const Eigen::VectorXd& lambda) {
  ContactSummary summary = summarize_contact_rows(model, qp, lambda);
  check_non_candidates(model, u, summary);
  return summary;
}

ContactSummary summarize_contact_rows(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& lambda) {
  ContactSummary summary;
  const bool solid = model.dim == 3;
  const double thickness = solid ? 1.0 : model.scene.body.thickness;
  const int n_obstacles = static_cast<int>(model.scene.obstacles.size());
  std::vector<Eigen::Vector3d> origins(n_obstacles, Eigen::Vector3d::UnitY());
  std::vector<std::vector<Eigen::Vector3d>> points(n_obstacles);  // 3D: the candidates' positions, in profile order
  std::vector<std::vector<double>> tributary(n_obstacles);
  summary.obstacles.resize(n_obstacles);
  for (int o = 0; o < n_obstacles; ++o) {
    summary.obstacles[o].obstacle = o;
    if (model.scene.obstacles[o].is<CircleObstacle>()) origins[o] = circle_origin(model, o);
  }
  for (int i = 0; i < qp.n_constraints(); ++i) {
    const Candidate& candidate = model.candidates[i];
    if (candidate.pair >= 0) continue;  // between two bodies: summarize_pairs
    const ObstacleSpec& obstacle = model.scene.obstacles[candidate.obstacle];
    const Eigen::Vector3d& x = model.mesh.nodes[candidate.node];
    ContactProfilePoint point;
    point.node = candidate.node;
    point.obstacle = candidate.obstacle;
    point.row = i;
    if (!solid) point.s = detail::surface_coordinate(obstacle, x, origins[candidate.obstacle]);
    point.force = lambda[i];
    summary.obstacles[candidate.obstacle].profile.push_back(point);
    summary.obstacles[candidate.obstacle].resultant += lambda[i] * detail::project(obstacle, x).normal;
    points[candidate.obstacle].push_back(x);
    tributary[candidate.obstacle].push_back(candidate.tributary);
  }
  const std::vector<double> pressure = nodal_pressures(model, qp, lambda);
  {
    std::vector<size_t> next(n_obstacles, 0);
    for (int i = 0; i < qp.n_constraints(); ++i) {
      const int o = model.candidates[i].obstacle;
      if (o < 0) continue;
      summary.obstacles[o].profile[next[o]++].pressure = pressure[i];
    }
  }
  const double lambda_max = lambda.size() ? lambda.maxCoeff() : 0.0;
  for (ObstacleContact& contact : summary.obstacles) {
    if (solid) {
      measure_3d(model, contact, points[contact.obstacle], tributary[contact.obstacle], lambda_max);
      // The profile by distance from the centre: p(r).
      std::stable_sort(contact.profile.begin(), contact.profile.end(),
                       [](const ContactProfilePoint& a, const ContactProfilePoint& b) { return a.s < b.s; });
    } else {
      std::sort(contact.profile.begin(), contact.profile.end(),
                [](const ContactProfilePoint& a, const ContactProfilePoint& b) { return a.s < b.s; });
      measure(contact, model.scene.body.symmetry, model.rotation.col(1), thickness, lambda_max);
    }
    summary.profile.insert(summary.profile.end(), contact.profile.begin(), contact.profile.end());
    summary.total_force += contact.total_force;
    summary.max_pressure = std::max(summary.max_pressure, contact.max_pressure);
    summary.contact_nodes += contact.contact_nodes;
    if (contact.total_force > summary.obstacles[summary.main_obstacle].total_force)
      summary.main_obstacle = contact.obstacle;
  }
  summary.line_load = summary.total_force / thickness;
  if (!summary.obstacles.empty()) {
    const ObstacleContact& main = summary.obstacles[summary.main_obstacle];
    summary.half_width = main.half_width;
    summary.half_width_last_node = main.half_width_last_node;
    summary.centre = main.centre;
    summary.contact_radius = main.contact_radius;
    summary.contact_radius_last_node = main.contact_radius_last_node;
    summary.contact_area = main.contact_area;
  }
  return summary;
}

}  // namespace contactqp
