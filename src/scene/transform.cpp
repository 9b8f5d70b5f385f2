// The scene transform: a rigid rotation of everything in the scene about the origin.
//
// The body is meshed and its boundary conditions are built in the scene's own (local) frame;
// build_model then rotates node positions, and rotated() turns the obstacles and the load
// vectors. Prescribed displacement components stay in the local frame (build_model gives
// those nodes a rotated DOF frame), so "[null, -δ]" still means "pushed along the body's axis,
// free across it" whatever the angle.
#include <cmath>

#include "contactqp/errors.hpp"
#include "readers.hpp"

namespace contactqp {

Eigen::Matrix2d TransformSpec::rotation() const {
  // Exact for multiples of 90°, so that a quarter turn moves no node by round-off.
  const double turns = rotate_degrees / 90.0;
  if (turns == std::round(turns)) {
    const long quarter = ((static_cast<long>(std::round(turns)) % 4) + 4) % 4;
    const double c[] = {1, 0, -1, 0}, s[] = {0, 1, 0, -1};
    Eigen::Matrix2d R;
    R << c[quarter], -s[quarter], s[quarter], c[quarter];
    return R;
  }
  const double angle = rotate_degrees * 3.14159265358979323846 / 180.0;
  Eigen::Matrix2d R;
  R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  return R;
}

Scene rotated(const Scene& scene) {
  Scene out = scene;
  out.transform = TransformSpec{};
  if (scene.transform.is_identity()) return out;
  const Eigen::Matrix2d R = scene.transform.rotation();
  for (ObstacleSpec& obstacle : out.obstacles) {
    obstacle.point = R * obstacle.point;
    obstacle.normal = R * obstacle.normal;
    obstacle.center = R * obstacle.center;
    for (Eigen::Vector2d& point : obstacle.points) point = R * point;
  }
  for (LoadSpec& load : out.loads) {
    load.vector = R * load.vector;  // traction, g, point force; a displacement stays local
    if (load.at) load.at = R * *load.at;
  }
  return out;
}

namespace detail {

TransformSpec read_transform(JsonObject transform) {
  TransformSpec spec;
  spec.rotate_degrees = transform.number("rotate_degrees");
  transform.finish();
  return spec;
}

}  // namespace detail
}  // namespace contactqp
