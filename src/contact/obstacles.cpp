// Rigid obstacles: the gap of a point along the obstacle normal at its closest point, and the
// coordinate of that closest point along the surface.
#include <cmath>
#include <limits>

#include "contact.hpp"

namespace contactqp::detail {
namespace {

// Unit normal of segment a→b on the body's side.
Eigen::Vector2d segment_normal(const Eigen::Vector2d& a, const Eigen::Vector2d& b, bool body_on_left) {
  const Eigen::Vector2d d = (b - a).normalized();
  return body_on_left ? Eigen::Vector2d(-d.y(), d.x()) : Eigen::Vector2d(d.y(), -d.x());
}

// The closest point of a profile: segment k, parameter t along it (the end segments extend
// beyond the ends), and the arc length there from the first point.
struct ProfileFoot {
  int segment = 0;
  double t = 0;
  double distance = std::numeric_limits<double>::infinity();
  double arc_length = 0;
};

ProfileFoot profile_foot(const std::vector<Eigen::Vector2d>& p, const Eigen::Vector2d& x) {
  ProfileFoot best;
  const int n_segments = static_cast<int>(p.size()) - 1;
  double length_before = 0;
  for (int k = 0; k < n_segments; ++k) {
    const Eigen::Vector2d d = p[k + 1] - p[k];
    const double length = d.norm();
    double t = (x - p[k]).dot(d) / (length * length);
    if (k > 0) t = std::max(t, 0.0);
    if (k < n_segments - 1) t = std::min(t, 1.0);
    const double distance = (x - (p[k] + t * d)).norm();
    if (distance < best.distance) best = {k, t, distance, length_before + t * length};
    length_before += length;
  }
  return best;
}

ObstacleProjection project_profile(const ObstacleSpec& obstacle, const Eigen::Vector2d& x) {
  const auto& p = obstacle.points;
  const ProfileFoot foot = profile_foot(p, x);
  const int k = foot.segment;
  const Eigen::Vector2d n_k = segment_normal(p[k], p[k + 1], obstacle.body_on_left);
  const int last = static_cast<int>(p.size()) - 2;
  const bool at_start = foot.t <= 0 && k > 0, at_end = foot.t >= 1 && k < last;
  if (!at_start && !at_end) return {(x - p[k]).dot(n_k), n_k};
  // The closest point is a vertex: the gap is the distance to it, signed by the side of the
  // vertex's pseudo-normal (the bisector of its two segments' normals), and the normal points
  // from the vertex to x.
  const int vertex = at_start ? k : k + 1;
  const Eigen::Vector2d n_other = at_start ? segment_normal(p[k - 1], p[k], obstacle.body_on_left)
                                           : segment_normal(p[k + 1], p[k + 2], obstacle.body_on_left);
  const Eigen::Vector2d pseudo = (n_k + n_other).normalized();
  const Eigen::Vector2d d = x - p[vertex];
  const double distance = d.norm();
  if (!(distance > 0)) return {0.0, pseudo};
  const double sign = d.dot(pseudo) >= 0 ? 1.0 : -1.0;
  return {sign * distance, sign * d / distance};
}

}  // namespace

ObstacleProjection project(const ObstacleSpec& obstacle, const Eigen::Vector2d& x) {
  if (obstacle.type == "circle") {
    const Eigen::Vector2d d = x - obstacle.center;
    const double distance = d.norm();
    if (!(distance > 0)) return {-obstacle.radius, Eigen::Vector2d::UnitY()};  // at the centre: any direction
    return {distance - obstacle.radius, d / distance};
  }
  if (obstacle.type == "profile") return project_profile(obstacle, x);
  return {(x - obstacle.point).dot(obstacle.normal), obstacle.normal};
}

double surface_coordinate(const ObstacleSpec& obstacle, const Eigen::Vector2d& x, const Eigen::Vector2d& origin) {
  if (obstacle.type == "circle") {
    // Arc length from `origin`, increasing along t = (n_y, −n_x), i.e. clockwise.
    const Eigen::Vector2d d = x - obstacle.center;
    const double angle = std::atan2(origin.x() * d.y() - origin.y() * d.x(), origin.dot(d));
    return -obstacle.radius * angle;
  }
  if (obstacle.type == "profile") return profile_foot(obstacle.points, x).arc_length;
  const Eigen::Vector2d tangent(obstacle.normal.y(), -obstacle.normal.x());
  return (x - obstacle.point).dot(tangent);
}

double obstacle_curvature(const ObstacleSpec& obstacle) {
  if (obstacle.type == "circle") return 1.0 / obstacle.radius;
  return 0.0;
}

}  // namespace contactqp::detail
