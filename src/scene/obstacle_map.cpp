#include "obstacle_map.hpp"

#include "per_kind.hpp"

namespace contactqp::detail {

ObstacleSpec mapped(const ObstacleSpec& obstacle, const RigidMap& map) {
  ObstacleSpec out = obstacle;
  const auto& point = map.point;
  const auto& direction = map.direction;
  std::visit(PerKind{
                 [&](PlaneObstacle& o) {
                   o.point = point(o.point);
                   o.normal = direction(o.normal);
                 },
                 [&](CircleObstacle& o) { o.center = point(o.center); },
                 [&](ProfileObstacle& o) {
                   for (Eigen::Vector3d& x : o.points) x = point(x);
                   if (map.reflection) o.body_on_left = !o.body_on_left;
                 },
                 [&](SphereObstacle& o) { o.center = point(o.center); },
                 [&](CylinderObstacle& o) {
                   o.point = point(o.point);
                   o.axis = direction(o.axis);
                 },
                 [&](PunchObstacle& o) {
                   o.center = point(o.center);
                   o.axis = direction(o.axis);
                 },
             },
             out.shape);
  return out;
}

}  // namespace contactqp::detail
