// 3D obstacles: planes, spheres, cylinders and the flat punch measure the gap along the normal
// at the closest point; checked against closed forms and against the gradient of the gap.
#include <catch2/catch.hpp>
#include <cmath>

#include "contact/contact.hpp"
#include "contactqp/scene.hpp"

using namespace contactqp;
using detail::project;

namespace {

ObstacleSpec sphere(Eigen::Vector3d center, double radius) {
  SphereObstacle o;
  o.center = center;
  o.radius = radius;
  return {"obstacle", o};
}

ObstacleSpec cylinder(Eigen::Vector3d point, Eigen::Vector3d axis, double radius) {
  CylinderObstacle o;
  o.point = point;
  o.axis = axis.normalized();
  o.radius = radius;
  return {"obstacle", o};
}

ObstacleSpec punch(Eigen::Vector3d center, Eigen::Vector3d axis, double radius) {
  PunchObstacle o;
  o.center = center;
  o.axis = axis.normalized();
  o.radius = radius;
  return {"obstacle", o};
}

ObstacleSpec plane_3d(Eigen::Vector3d point, Eigen::Vector3d normal) {
  PlaneObstacle o;
  o.point = point;
  o.normal = normal.normalized();
  return {"obstacle", o};
}

}  // namespace

TEST_CASE("a sphere and a cylinder measure the distance to their surface", "[unit][obstacle][3d]") {
  const ObstacleSpec ball = sphere({1, -2, 0.5}, 0.5);
  const Eigen::Vector3d x(2, 0, 1);
  CHECK(project(ball, x).gap == Approx((x - Eigen::Vector3d(1, -2, 0.5)).norm() - 0.5));
  const ObstacleSpec pipe = cylinder({0, 0, 0}, {1, 1, 0}, 0.25);
  // (0, 0, 2) is 2 from the axis along z; (1, 1, 2) is the same distance.
  CHECK(project(pipe, Eigen::Vector3d(0, 0, 2)).gap == Approx(1.75));
  CHECK(project(pipe, Eigen::Vector3d(1, 1, 2)).gap == Approx(1.75));
  CHECK(project(pipe, Eigen::Vector3d(1, 1, 2)).normal.isApprox(Eigen::Vector3d::UnitZ()));
}

TEST_CASE("a flat punch: its face above the disc, the rim beyond it, the side below", "[unit][obstacle][3d]") {
  const ObstacleSpec p = punch({0, 0, 0}, {0, 0, 1}, 0.5);
  // Over the face: the height, along the axis.
  CHECK(project(p, Eigen::Vector3d(0.3, 0.2, 0.1)).gap == Approx(0.1));
  CHECK(project(p, Eigen::Vector3d(0.3, 0.2, 0.1)).normal.isApprox(Eigen::Vector3d::UnitZ()));
  // Beyond the rim at the face's level: the distance to the rim, normal across the axis, so a
  // flat body's face there does not face the punch.
  const auto beside = project(p, Eigen::Vector3d(0.8, 0, 0));
  CHECK(beside.gap == Approx(0.3));
  CHECK(beside.normal.isApprox(Eigen::Vector3d::UnitX()));
  // Above and beyond the rim: the distance to the rim circle.
  CHECK(project(p, Eigen::Vector3d(0, 0.9, 0.3)).gap == Approx(0.5));
  // Below the face, beside the punch: the distance to its side.
  CHECK(project(p, Eigen::Vector3d(0, -0.7, -1)).gap == Approx(0.2));
}

TEST_CASE("the 3D normal is the gradient of the gap, for every 3D obstacle type", "[unit][obstacle][3d]") {
  const ObstacleSpec obstacles[] = {plane_3d({0, 0, 0.1}, {0.3, -0.2, 1}), sphere({0, -1, 0.2}, 1),
                                    cylinder({0.1, 0, -1}, {1, 0.5, 0.2}, 0.7), punch({0, 0, 0}, {0.1, 0.2, 1}, 0.5)};
  const Eigen::Vector3d points[] = {
      {0.3, 0.7, 0.4}, {-0.4, 0.9, 1.1}, {1.2, 1.9, 0.3}, {0.05, 0.1, 1.4}, {0.9, 0.2, 0.3}};
  const double h = 1e-6;
  for (const ObstacleSpec& o : obstacles) {
    for (const Eigen::Vector3d& x : points) {
      CAPTURE(o.type(), x.transpose());
      const auto p = project(o, x);
      Eigen::Vector3d gradient;
      for (int c = 0; c < 3; ++c) {
        const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(c);
        gradient[c] = (project(o, Eigen::Vector3d(x + e)).gap - project(o, Eigen::Vector3d(x - e)).gap) / (2 * h);
      }
      CHECK((gradient - p.normal).norm() < 1e-6);
      CHECK(p.normal.norm() == Approx(1.0));
    }
  }
}
