// One entry of the `obstacle` section: a plane, a circle, or a piecewise-linear profile.
#include <algorithm>
#include <cmath>

#include "contactqp/errors.hpp"
#include "readers.hpp"

namespace contactqp::detail {
namespace {

const std::vector<std::string> kObstacleTypes = {"plane", "circle", "profile"};

double cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

// Do the closed segments [a, b] and [c, d] share a point?
bool segments_meet(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  auto on_segment = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r, double side) {
    return side == 0 && std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) &&
           std::min(p.y(), q.y()) <= r.y() && r.y() <= std::max(p.y(), q.y());
  };
  return on_segment(a, b, c, d1) || on_segment(a, b, d, d2) || on_segment(c, d, a, d3) || on_segment(c, d, b, d4);
}

// The profile must be a simple path: distinct consecutive points, no segment folding back on
// the previous one, no two segments crossing. Otherwise "the side of the body" is undefined.
void check_profile(const std::vector<Eigen::Vector2d>& p, const std::string& path) {
  const size_t n = p.size();
  double extent = 0;
  for (size_t i = 1; i < n; ++i) extent = std::max(extent, (p[i] - p[0]).norm());
  for (size_t i = 0; i + 1 < n; ++i)
    if (!((p[i + 1] - p[i]).norm() > 1e-12 * extent))
      throw InputError(path + "[" + std::to_string(i + 1) + "]", "repeats the point before it: consecutive points must differ");
  for (size_t i = 0; i + 2 < n; ++i) {
    const Eigen::Vector2d u = (p[i + 1] - p[i]).normalized(), v = (p[i + 2] - p[i + 1]).normalized();
    if (u.dot(v) < -1 + 1e-12)
      throw InputError(path + "[" + std::to_string(i + 2) + "]", "turns the profile back on itself");
  }
  for (size_t i = 0; i + 1 < n; ++i)
    for (size_t j = i + 2; j + 1 < n; ++j)
      if (segments_meet(p[i], p[i + 1], p[j], p[j + 1]))
        throw InputError(path, "crosses itself: segment " + std::to_string(i) + " meets segment " + std::to_string(j));
}

void read_profile(JsonObject& obstacle, ObstacleSpec& spec) {
  const nlohmann::json& points = obstacle.value("points");
  const std::string path = obstacle.path_of("points");
  if (!points.is_array() || points.size() < 2)
    throw InputError(path, "= " + describe(points) + ": must be an array of at least two points [[x, y], ...]");
  for (size_t i = 0; i < points.size(); ++i) spec.points.push_back(read_vector(points[i], path + "[" + std::to_string(i) + "]"));
  check_profile(spec.points, path);
  const std::string side = obstacle.string("body_side");
  if (side != "left" && side != "right") unknown_choice(obstacle.path_of("body_side"), side, "side", {"left", "right"});
  spec.body_on_left = side == "left";
}

}  // namespace

ObstacleSpec read_obstacle(JsonObject obstacle) {
  ObstacleSpec spec;
  spec.path = obstacle.path();
  spec.type = obstacle.string("type");
  if (std::find(kObstacleTypes.begin(), kObstacleTypes.end(), spec.type) == kObstacleTypes.end())
    unknown_choice(obstacle.path_of("type"), spec.type, "obstacle type", kObstacleTypes);
  if (spec.type == "plane") {
    spec.point = read_vector(obstacle.value("point"), obstacle.path_of("point"));
    spec.normal = read_vector(obstacle.value("normal"), obstacle.path_of("normal"));
    const double length = spec.normal.norm();
    if (!(length > 0)) throw InputError(obstacle.path_of("normal"), "= [0, 0]: must be a non-zero vector");
    spec.normal /= length;
  } else if (spec.type == "circle") {
    spec.center = read_vector(obstacle.value("center"), obstacle.path_of("center"));
    spec.radius = obstacle.number("radius");
    require(spec.radius > 0, obstacle.path_of("radius"), spec.radius, "must be positive");
  } else {
    read_profile(obstacle, spec);
  }
  obstacle.finish();
  return spec;
}

}  // namespace contactqp::detail
