// body.symmetry models only x ≥ 0, with u_x = 0 on x = 0. That is right only when the whole
// scene is mirror-symmetric about x = 0 in its own frame (the transform turns the symmetric
// scene as a whole, so the check ignores it).
#include <cmath>

#include "contactqp/errors.hpp"
#include "readers.hpp"

namespace contactqp::detail {
namespace {

[[noreturn]] void broken(const std::string& what) {
  throw InputError("body.symmetry", "= true: " + what + ", which is not mirror-symmetric about x = 0; set \"symmetry\": false");
}

bool mirror_symmetric(const ObstacleSpec& o) {
  if (o.type == "plane") return std::abs(o.normal.x()) <= 1e-12 && o.point.x() == 0;
  if (o.type == "circle") return o.center.x() == 0;
  // A profile is its own mirror image walked backwards: point i mirrors point n − 1 − i.
  const size_t n = o.points.size();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& p = o.points[i];
    const Eigen::Vector2d& q = o.points[n - 1 - i];
    const double scale = std::max({1e-300, p.norm(), q.norm()});
    if (std::abs(p.x() + q.x()) > 1e-12 * scale || std::abs(p.y() - q.y()) > 1e-12 * scale) return false;
  }
  return true;
}

}  // namespace

void check_symmetry(const Scene& scene) {
  if (!scene.body.symmetry) return;
  for (const ObstacleSpec& o : scene.obstacles)
    if (!mirror_symmetric(o))
      broken(o.path + " (" + o.type + (o.type == "plane"    ? ": its point must have x = 0 and its normal no x component)"
                                       : o.type == "circle" ? ": its center must have x = 0)"
                                                            : ": its points must mirror each other end to end)"));
  for (const LoadSpec& load : scene.loads) {
    if (load.type == "displacement" && load.value[0] && *load.value[0] != 0.0)
      broken(load.path + " has ux = " + format_value(*load.value[0]));
    if ((load.type == "traction" || load.type == "gravity") && load.vector.x() != 0.0)
      broken(load.path + " has an x component " + format_value(load.vector.x()));
    if (load.type == "point" && load.at && load.at->x() < 0)
      broken(load.path + " acts at x = " + format_value(load.at->x()) + " < 0, outside the modelled half (give x ≥ 0: the mirror image is implied)");
    if (load.type == "point" && load.at && load.at->x() == 0 && load.vector.x() != 0)
      broken(load.path + " acts on x = 0 with an x component " + format_value(load.vector.x()));
  }
}

}  // namespace contactqp::detail
