// Rigid obstacles: the gap of a point along the obstacle normal at its closest point, and (2D)
// the coordinate of that closest point along the surface.
#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "contact.hpp"

namespace contactqp::detail {
namespace {

// A point this close to a punch's rim circle, relative to its radius, is on its face.
constexpr double kRimTolerance = 1e-9;

// Unit normal of segment a→b (in the plane z = 0) on the body's side.
Eigen::Vector3d segment_normal(const Eigen::Vector3d& a, const Eigen::Vector3d& b, bool body_on_left) {
  const Eigen::Vector3d d = (b - a).normalized();
  return body_on_left ? Eigen::Vector3d(-d.y(), d.x(), 0.0) : Eigen::Vector3d(d.y(), -d.x(), 0.0);
}

// The closest point of a profile: segment k, parameter t along it (the end segments extend
// beyond the ends), and the arc length there from the first point.
struct ProfileFoot {
  int segment = 0;
  double t = 0;
  double distance = std::numeric_limits<double>::infinity();
  double arc_length = 0;
};

ProfileFoot profile_foot(const std::vector<Eigen::Vector3d>& p, const Eigen::Vector3d& x) {
  ProfileFoot best;
  const int n_segments = static_cast<int>(p.size()) - 1;
  double length_before = 0;
  for (int k = 0; k < n_segments; ++k) {
    const Eigen::Vector3d d = p[k + 1] - p[k];
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

ObstacleProjection project_profile(const ProfileObstacle& obstacle, const Eigen::Vector3d& x) {
  const auto& p = obstacle.points;
  const ProfileFoot foot = profile_foot(p, x);
  const int k = foot.segment;
  const Eigen::Vector3d n_k = segment_normal(p[k], p[k + 1], obstacle.body_on_left);
  const int last = static_cast<int>(p.size()) - 2;
  const bool at_start = foot.t <= 0 && k > 0, at_end = foot.t >= 1 && k < last;
  if (!at_start && !at_end) return {(x - p[k]).dot(n_k), n_k};
  // The closest point is a vertex: the gap is the distance to it, signed by the side of the
  // vertex's pseudo-normal (the bisector of its two segments' normals), and the normal points
  // from the vertex to x.
  const int vertex = at_start ? k : k + 1;
  const Eigen::Vector3d n_other = at_start ? segment_normal(p[k - 1], p[k], obstacle.body_on_left)
                                           : segment_normal(p[k + 1], p[k + 2], obstacle.body_on_left);
  const Eigen::Vector3d pseudo = (n_k + n_other).normalized();
  const Eigen::Vector3d d = x - p[vertex];
  const double distance = d.norm();
  if (!(distance > 0)) return {0.0, pseudo};
  const double sign = d.dot(pseudo) >= 0 ? 1.0 : -1.0;
  return {sign * distance, sign * d / distance};
}

// Outside a ball (circle in 2D) of the given centre and radius.
ObstacleProjection project_ball(const Eigen::Vector3d& center, double radius, const Eigen::Vector3d& x) {
  const Eigen::Vector3d d = x - center;
  const double distance = d.norm();
  if (!(distance > 0)) return {-radius, Eigen::Vector3d::UnitY()};  // at the centre: any direction
  return {distance - radius, d / distance};
}

ObstacleProjection project_cylinder(const CylinderObstacle& c, const Eigen::Vector3d& x) {
  const Eigen::Vector3d y = x - c.point;
  const Eigen::Vector3d radial = y - y.dot(c.axis) * c.axis;
  const double distance = radial.norm();
  if (!(distance > 0)) return {-c.radius, c.axis.unitOrthogonal()};  // on the axis: any direction across it
  return {distance - c.radius, radial / distance};
}

// The punch is the solid {h ≤ 0, r ≤ a} behind its face (h the height above the face along
// the axis, r the distance from the axis): above the face the gap is h; beyond the rim the
// distance to the rim circle (or to the side, below the face's level).
ObstacleProjection project_punch(const PunchObstacle& punch, const Eigen::Vector3d& x) {
  const Eigen::Vector3d y = x - punch.center;
  const double h = y.dot(punch.axis);
  const Eigen::Vector3d radial = y - h * punch.axis;
  const double r = radial.norm();
  // Nodes placed on the rim belong to the face, whatever the round-off in their radius.
  if (r <= punch.radius * (1 + kRimTolerance)) return {h, punch.axis};
  const Eigen::Vector3d outward = radial / r;
  if (h < 0) return {r - punch.radius, outward};
  const Eigen::Vector3d d = y - punch.radius * outward;  // from the rim point
  const double distance = d.norm();
  return {distance, d / distance};
}

}  // namespace

ObstacleProjection project(const ObstacleSpec& obstacle, const Eigen::Vector3d& x) {
  if (const auto* plane = obstacle.as<PlaneObstacle>()) return {(x - plane->point).dot(plane->normal), plane->normal};
  if (const auto* circle = obstacle.as<CircleObstacle>()) return project_ball(circle->center, circle->radius, x);
  if (const auto* sphere = obstacle.as<SphereObstacle>()) return project_ball(sphere->center, sphere->radius, x);
  if (const auto* profile = obstacle.as<ProfileObstacle>()) return project_profile(*profile, x);
  if (const auto* cylinder = obstacle.as<CylinderObstacle>()) return project_cylinder(*cylinder, x);
  return project_punch(std::get<PunchObstacle>(obstacle.shape), x);
}

ObstacleProjection project(const ObstacleSpec& obstacle, const Eigen::Vector2d& x) {
  return project(obstacle, Eigen::Vector3d(x.x(), x.y(), 0.0));
}

double surface_coordinate(const ObstacleSpec& obstacle, const Eigen::Vector3d& x, const Eigen::Vector3d& origin) {
  if (const auto* circle = obstacle.as<CircleObstacle>()) {
    // Arc length from `origin`, increasing along t = (n_y, −n_x), i.e. clockwise.
    const Eigen::Vector3d d = x - circle->center;
    const double angle = std::atan2(origin.x() * d.y() - origin.y() * d.x(), origin.dot(d));
    return -circle->radius * angle;
  }
  if (const auto* profile = obstacle.as<ProfileObstacle>()) return profile_foot(profile->points, x).arc_length;
  const auto& plane = std::get<PlaneObstacle>(obstacle.shape);
  const Eigen::Vector3d tangent(plane.normal.y(), -plane.normal.x(), 0.0);
  return (x - plane.point).dot(tangent);
}

double surface_coordinate(const ObstacleSpec& obstacle, const Eigen::Vector2d& x, const Eigen::Vector2d& origin) {
  return surface_coordinate(obstacle, Eigen::Vector3d(x.x(), x.y(), 0.0), Eigen::Vector3d(origin.x(), origin.y(), 0.0));
}

std::optional<double> obstacle_curvature(const ObstacleSpec& obstacle) {
  if (const auto* circle = obstacle.as<CircleObstacle>()) return 1.0 / circle->radius;
  if (const auto* sphere = obstacle.as<SphereObstacle>()) return 1.0 / sphere->radius;
  if (obstacle.is<CylinderObstacle>()) return std::nullopt;
  return 0.0;
}

}  // namespace contactqp::detail
