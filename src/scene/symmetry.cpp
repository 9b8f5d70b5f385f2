// body.symmetry models only x ≥ 0 in 2D, the quarter x ≥ 0, y ≥ 0 in 3D (or the half beside the
// one plane "symmetry": "x" or "y" names), with the normal displacement held on each cut. That
// is right only when the whole scene is mirror-symmetric about x = 0 (and y = 0) in its own frame (the transform turns the symmetric scene as a
// whole, so the check ignores it).
#include <algorithm>
#include <cmath>

#include "contactqp/errors.hpp"
#include "per_kind.hpp"
#include "readers.hpp"

namespace contactqp::detail {
namespace {

[[noreturn]] void broken(const BodySpec& body, const std::string& what, const std::string& plane) {
  const std::string name = symmetry_name(body), value = name == "true" ? name : "\"" + name + "\"";
  throw InputError("body.symmetry", "= " + value + ": " + what + ", which is not mirror-symmetric about " + plane +
                                        "; set \"symmetry\": false");
}

// A point on the mirror plane x_c = 0; a direction within it.
bool on_plane(const Eigen::Vector3d& point, int c) { return point[c] == 0; }
bool in_plane(const Eigen::Vector3d& direction, int c) { return std::abs(direction[c]) <= 1e-12; }

// Whether the obstacle is its own mirror image about the plane x_c = 0, and if not, the rule it
// breaks (axis: "x" or "y"), kind by kind.
struct Mirror {
  bool symmetric;
  std::string rule;
};

Mirror mirror(const ObstacleSpec& o, int c, const std::string& axis) {
  const std::string center_rule = ": its center must have " + axis + " = 0)";
  return std::visit(
      PerKind{
          [&](const PlaneObstacle& p) {
            return Mirror{in_plane(p.normal, c) && on_plane(p.point, c),
                          ": its point must have " + axis + " = 0 and its normal no " + axis + " component)"};
          },
          [&](const CircleObstacle& circle) {
            return Mirror{on_plane(circle.center, c), center_rule};
          },
          [&](const SphereObstacle& sphere) {
            return Mirror{on_plane(sphere.center, c), center_rule};
          },
          [&](const PunchObstacle& punch) {
            return Mirror{on_plane(punch.center, c) && in_plane(punch.axis, c),
                          ": its center must have " + axis + " = 0 and its axis no " + axis + " component)"};
          },
          [&](const CylinderObstacle& cylinder) {
            return Mirror{(in_plane(cylinder.axis, c) && on_plane(cylinder.point, c)) ||
                              std::abs(std::abs(cylinder.axis[c]) - 1) <= 1e-12,
                          ": its axis must lie in the plane " + axis +
                              " = 0 or cross it at right angles through a point with " + axis + " = 0)"};
          },
          [&](const ProfileObstacle& profile) {
            // A profile is its own mirror image walked backwards: point i mirrors point n − 1 − i.
            const auto& points = profile.points;
            const size_t n = points.size();
            bool symmetric = true;
            for (size_t i = 0; i < n; ++i) {
              const Eigen::Vector3d& p = points[i];
              const Eigen::Vector3d& q = points[n - 1 - i];
              const double scale = std::max({1e-300, p.norm(), q.norm()});
              if (std::abs(p.x() + q.x()) > 1e-12 * scale || std::abs(p.y() - q.y()) > 1e-12 * scale) symmetric = false;
            }
            return Mirror{symmetric, ": its points must mirror each other end to end)"};
          },
      },
      o.shape);
}

}  // namespace

void check_symmetry(const Scene& scene) {
  if (!scene.body.symmetry) return;
  const int dim = scene.dim();
  for (int c = 0; c < dim - 1; ++c) {  // x = 0, and y = 0 in 3D
    if (!symmetric_about(scene.body, c, dim)) continue;
    const std::string axis = c == 0 ? "x" : "y";
    const std::string plane = axis + " = 0";
    for (const ObstacleSpec& o : scene.obstacles)
      if (const Mirror m = mirror(o, c, axis); !m.symmetric)
        broken(scene.body, o.path + " (" + o.type() + m.rule, plane);
    for (const LoadSpec& load : scene.loads) {
      if (const auto* d = load.as<DisplacementLoad>(); d && d->value[c] && *d->value[c] != 0.0)
        broken(scene.body, load.path + " has u" + axis + " = " + format_value(*d->value[c]), plane);
      // A rigid surface tied along the plane's normal would move its mirror image the other way.
      if (const auto* r = load.as<RigidForceLoad>(); r && r->value[c])
        broken(scene.body,
               load.path + " ties the rigid surface along " + axis + " (F" + axis + " = " + format_value(*r->value[c]) +
                   "; give null: the plane holds " + axis + ")",
               plane);
      // A turning surface's mirror image turns the other way (its tilt out of the plane).
      if (const auto* r = load.as<RigidForceLoad>(); r && r->turns())
        broken(scene.body, load.path + " has a moment (the rigid surface turns)", plane);
      const Eigen::Vector3d* along = nullptr;  // a traction and g must be parallel to the plane
      if (const auto* t = load.as<TractionLoad>()) along = &t->traction;
      if (const auto* g = load.as<GravityLoad>()) along = &g->g;
      if (along && (*along)[c] != 0.0)
        broken(scene.body, load.path + " has an " + axis + " component " + format_value((*along)[c]), plane);
      const auto* p = load.as<PointLoad>();
      if (p && p->at && (*p->at)[c] < 0)
        broken(scene.body,
               load.path + " acts at " + axis + " = " + format_value((*p->at)[c]) + " < 0, outside the modelled " +
                   (symmetry_copies(scene.body, dim) == 2 ? "half" : "quarter") + " (give " + axis +
                   " ≥ 0: the mirror image is implied)",
               plane);
      if (p && p->at && (*p->at)[c] == 0 && p->force[c] != 0)
        broken(scene.body,
               load.path + " acts on " + axis + " = 0 with an " + axis + " component " + format_value(p->force[c]),
               plane);
    }
  }
}

}  // namespace contactqp::detail
