// Boussinesq's rigid flat circular punch on an elastic half-space (docs/architecture.md):
//   P = 2 a E* δ,   p(r) = P / (2π a sqrt(a² − r²)),
// singular at the rim, so the shape is compared as p(r)·2πa·sqrt(a² − r²)/P away from it.
#include <algorithm>
#include <cmath>
#include <limits>

#include "contactqp/post.hpp"
#include "qp/pi.hpp"

namespace contactqp {
namespace {

// Beyond this fraction of the radius the pressure's rim singularity dominates the mesh error.
constexpr double kShapeReach = 0.8;

// The approach δ: the spread of the displacement loads' pushes along −axis, the punch itself
// standing at 0. nullopt when no load pushes along the axis.
std::optional<double> approach(const Model& model, const Eigen::Vector3d& axis) {
  double highest = 0, lowest = 0;
  bool any = false;
  for (const LoadSpec& load : model.scene.loads) {
    const DisplacementLoad* d = load.as<DisplacementLoad>();
    if (!d) continue;
    // Prescribed components are along the scene's own axes (turned by its transform).
    Eigen::Vector3d value = Eigen::Vector3d::Zero();
    bool along = false;
    for (int c = 0; c < 3; ++c) {
      if (!d->value[c]) continue;
      value[c] = *d->value[c];
      along = along || std::abs(model.rotation.col(c).dot(axis)) > 1e-9;
    }
    if (!along) continue;
    const double push = -(model.rotation * value).dot(axis);
    highest = std::max(highest, push);
    lowest = std::min(lowest, push);
    any = true;
  }
  if (!any) return std::nullopt;
  return highest - lowest;
}

}  // namespace

std::optional<PunchComparison> compare_with_boussinesq(const Model& model, const ContactSummary& contact) {
  if (model.dim != 3 || contact.obstacles.empty()) return std::nullopt;
  const ObstacleContact& zone = contact.obstacles[contact.main_obstacle];
  const auto* punch = model.scene.obstacles[zone.obstacle].as<PunchObstacle>();
  if (!punch) return std::nullopt;
  const auto delta = approach(model, punch->axis);
  if (!delta || !(*delta > 0) || !(zone.total_force > 0)) return std::nullopt;
  PunchComparison out;
  const double E = model.scene.material.E, nu = model.scene.material.nu, a = punch->radius;
  out.radius = a;
  out.approach = *delta;
  out.effective_modulus = E / (1 - nu * nu);
  out.force = 2 * a * out.effective_modulus * out.approach;
  out.error_force = (zone.total_force - out.force) / out.force;
  // The punch's centre, not the centre of pressure, is where r is measured from.
  const double loaded = 1e-8 * std::max(1e-300, [&] {
                          double m = 0;
                          for (const auto& p : zone.profile) m = std::max(m, p.force);
                          return m;
                        }());
  for (const ContactProfilePoint& point : zone.profile) {
    const Eigen::Vector3d d = model.mesh.nodes[point.node] - punch->center;
    const double r = (d - d.dot(punch->axis) * punch->axis).norm();
    if (r > kShapeReach * a || point.force <= loaded) continue;
    const double shape = point.pressure * 2 * kPi * a * std::sqrt(a * a - r * r) / zone.total_force;
    out.shape_error = std::max(out.shape_error, std::abs(shape - 1));
  }
  return out;
}

}  // namespace contactqp
