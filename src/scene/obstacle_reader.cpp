// One entry of the `obstacle` section: in 2D a plane, a circle, or a piecewise-linear profile;
// in 3D a plane, a sphere, a cylinder, or a flat circular punch. Each kind reads only its own
// fields into its own type.
#include <algorithm>
#include <cmath>

#include "contactqp/errors.hpp"
#include "per_kind.hpp"
#include "readers.hpp"

namespace contactqp::detail {
namespace {

const std::vector<std::string> kObstacleTypes2d = {"plane", "circle", "profile"};
const std::vector<std::string> kObstacleTypes3d = {"plane", "sphere", "cylinder", "punch"};

double cross(const Eigen::Vector3d& u, const Eigen::Vector3d& v) { return u.x() * v.y() - u.y() * v.x(); }

// Do the closed segments [a, b] and [c, d] (in the plane z = 0) share a point?
bool segments_meet(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  auto on_segment = [](const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r, double side) {
    return side == 0 && std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) &&
           std::min(p.y(), q.y()) <= r.y() && r.y() <= std::max(p.y(), q.y());
  };
  return on_segment(a, b, c, d1) || on_segment(a, b, d, d2) || on_segment(c, d, a, d3) || on_segment(c, d, b, d4);
}

// The profile must be a simple path: distinct consecutive points, no segment folding back on
// the previous one, no two segments crossing. Otherwise "the side of the body" is undefined.
void check_profile(const std::vector<Eigen::Vector3d>& p, const std::string& path) {
  const size_t n = p.size();
  double extent = 0;
  for (size_t i = 1; i < n; ++i) extent = std::max(extent, (p[i] - p[0]).norm());
  for (size_t i = 0; i + 1 < n; ++i)
    if (!((p[i + 1] - p[i]).norm() > 1e-12 * extent))
      throw InputError(path + "[" + std::to_string(i + 1) + "]",
                       "repeats the point before it: consecutive points must differ");
  for (size_t i = 0; i + 2 < n; ++i) {
    const Eigen::Vector3d u = (p[i + 1] - p[i]).normalized(), v = (p[i + 2] - p[i + 1]).normalized();
    if (u.dot(v) < -1 + 1e-12)
      throw InputError(path + "[" + std::to_string(i + 2) + "]", "turns the profile back on itself");
  }
  for (size_t i = 0; i + 1 < n; ++i)
    for (size_t j = i + 2; j + 1 < n; ++j)
      if (segments_meet(p[i], p[i + 1], p[j], p[j + 1]))
        throw InputError(path, "crosses itself: segment " + std::to_string(i) + " meets segment " + std::to_string(j));
}

ProfileObstacle read_profile(JsonObject& obstacle) {
  ProfileObstacle spec;
  const nlohmann::json& points = obstacle.value("points");
  const std::string path = obstacle.path_of("points");
  if (!points.is_array() || points.size() < 2)
    throw InputError(path, "= " + describe(points) + ": must be an array of at least two points [[x, y], ...]");
  for (size_t i = 0; i < points.size(); ++i)
    spec.points.push_back(read_vector(points[i], path + "[" + std::to_string(i) + "]", 2));
  check_profile(spec.points, path);
  const std::string side = obstacle.string("body_side");
  if (side != "left" && side != "right") unknown_choice(obstacle.path_of("body_side"), side, "side", {"left", "right"});
  spec.body_on_left = side == "left";
  return spec;
}

double read_radius(JsonObject& obstacle) {
  const double radius = obstacle.number("radius");
  require(radius > 0, obstacle.path_of("radius"), radius, "must be positive");
  return radius;
}

}  // namespace

ObstacleSpec read_obstacle(JsonObject obstacle, int dim) {
  ObstacleSpec spec;
  spec.path = obstacle.path();
  const std::string type = obstacle.string("type");
  const std::vector<std::string>& types = dim == 2 ? kObstacleTypes2d : kObstacleTypes3d;
  if (std::find(types.begin(), types.end(), type) == types.end()) {
    const std::vector<std::string>& other = dim == 2 ? kObstacleTypes3d : kObstacleTypes2d;
    if (std::find(other.begin(), other.end(), type) != other.end())
      throw InputError(obstacle.path_of("type"),
                       "= \"" + type + "\": a " + (dim == 2 ? "3D" : "2D") + " obstacle, and the scene's model is " +
                           (dim == 2 ? "2D (use \"model\": \"solid\")" : "solid (3D)") + "; valid: " + join(types));
    unknown_choice(obstacle.path_of("type"), type, "obstacle type", types);
  }
  auto vector = [&](const char* key) { return read_vector(obstacle.value(key), obstacle.path_of(key), dim); };
  auto direction = [&](const char* key) { return read_direction(obstacle.value(key), obstacle.path_of(key), dim); };
  if (type == "plane") {
    PlaneObstacle plane;
    plane.point = vector("point");
    plane.normal = direction("normal");
    spec.shape = plane;
  } else if (type == "circle") {
    CircleObstacle circle;
    circle.center = vector("center");
    circle.radius = read_radius(obstacle);
    spec.shape = circle;
  } else if (type == "profile") {
    spec.shape = read_profile(obstacle);
  } else if (type == "sphere") {
    SphereObstacle sphere;
    sphere.center = vector("center");
    sphere.radius = read_radius(obstacle);
    spec.shape = sphere;
  } else if (type == "cylinder") {
    CylinderObstacle cylinder;
    cylinder.point = vector("point");
    cylinder.axis = direction("axis");
    cylinder.radius = read_radius(obstacle);
    spec.shape = cylinder;
  } else {
    PunchObstacle punch;
    punch.center = vector("center");
    punch.axis = direction("axis");
    punch.radius = read_radius(obstacle);
    spec.shape = punch;
  }
  if (obstacle.has("friction")) spec.friction = read_friction(obstacle.object("friction"));
  obstacle.finish();
  return spec;
}

}  // namespace contactqp::detail

namespace contactqp {

std::string ObstacleSpec::type() const {
  return std::visit(
      detail::PerKind{[](const PlaneObstacle&) { return "plane"; }, [](const CircleObstacle&) { return "circle"; },
                      [](const ProfileObstacle&) { return "profile"; }, [](const SphereObstacle&) { return "sphere"; },
                      [](const CylinderObstacle&) { return "cylinder"; }, [](const PunchObstacle&) { return "punch"; }},
      shape);
}

}  // namespace contactqp
