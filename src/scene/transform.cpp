// The scene transform: a rigid rotation of everything in the scene about the origin (about z
// in 2D, about a given axis in 3D).
//
// The body is meshed and its boundary conditions are built in the scene's own (local) frame;
// build_model then rotates node positions, and rotated() turns the obstacles and the load
// vectors. Prescribed displacement components stay in the local frame (build_model gives
// those nodes a rotated DOF frame), so "[null, -δ]" still means "pushed along the body's axis,
// free across it" whatever the angle.
#include <cmath>

#include "contactqp/errors.hpp"
#include "obstacle_map.hpp"
#include "readers.hpp"

namespace contactqp {
namespace {

// cos and sin of the angle, exact for multiples of 90°, so that a quarter turn moves no node
// by round-off.
std::pair<double, double> cos_sin(double degrees) {
  const double turns = degrees / 90.0;
  if (turns == std::round(turns)) {
    const long quarter = ((static_cast<long>(std::round(turns)) % 4) + 4) % 4;
    const double c[] = {1, 0, -1, 0}, s[] = {0, 1, 0, -1};
    return {c[quarter], s[quarter]};
  }
  const double angle = degrees * 3.14159265358979323846 / 180.0;
  return {std::cos(angle), std::sin(angle)};
}

}  // namespace

Eigen::Matrix3d TransformSpec::rotation() const {
  const auto [c, s] = cos_sin(rotate_degrees);
  Eigen::Matrix3d R;
  if (axis == Eigen::Vector3d::UnitZ()) {
    R << c, -s, 0, s, c, 0, 0, 0, 1;
    return R;
  }
  // Rodrigues: R = c I + s [a]× + (1 − c) a aᵀ.
  Eigen::Matrix3d cross;
  cross << 0, -axis.z(), axis.y(), axis.z(), 0, -axis.x(), -axis.y(), axis.x(), 0;
  R = c * Eigen::Matrix3d::Identity() + s * cross + (1 - c) * axis * axis.transpose();
  return R;
}

Scene rotated(const Scene& scene) {
  Scene out = scene;
  out.transform = TransformSpec{};
  if (scene.transform.is_identity()) return out;
  const Eigen::Matrix3d R = scene.transform.rotation();
  const detail::RigidMap turn{[&R](const Eigen::Vector3d& x) { return Eigen::Vector3d(R * x); },
                              [&R](const Eigen::Vector3d& d) { return Eigen::Vector3d(R * d); }};
  for (ObstacleSpec& obstacle : out.obstacles) obstacle = detail::mapped(obstacle, turn);
  // Traction, g and point force turn; a displacement's components stay along the scene's axes
  // and a pressure is normal to the (turned) boundary.
  for (LoadSpec& load : out.loads) {
    if (auto* traction = load.as<TractionLoad>()) traction->traction = R * traction->traction;
    if (auto* gravity = load.as<GravityLoad>()) gravity->g = R * gravity->g;
    if (auto* point = load.as<PointLoad>()) {
      point->force = R * point->force;
      if (point->at) point->at = R * *point->at;
    }
  }
  return out;
}

namespace detail {

TransformSpec read_transform(JsonObject transform, int dim) {
  TransformSpec spec;
  spec.rotate_degrees = transform.number("rotate_degrees");
  // A turn is a turn: anything beyond one is a mistake (and 1e308 once overflowed the quarter count).
  require(std::abs(spec.rotate_degrees) <= 360, transform.path_of("rotate_degrees"), spec.rotate_degrees,
          "must lie in [-360, 360]");
  // 2D scenes turn about z only: an axis there is an unknown key.
  if (dim == 3) spec.axis = read_direction(transform.value("axis"), transform.path_of("axis"), 3);
  transform.finish();
  return spec;
}

}  // namespace detail
}  // namespace contactqp
