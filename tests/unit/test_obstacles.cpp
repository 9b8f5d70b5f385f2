// Obstacles: the gap along the normal at the closest point, for planes, circles and profiles,
// checked against closed forms and against the gradient of the distance.
#include <catch2/catch.hpp>
#include <cmath>

#include "contact/contact.hpp"
#include "contactqp/scene.hpp"

using namespace contactqp;
using detail::project;

namespace {

Eigen::Vector3d lift(const Eigen::Vector2d& x) { return {x.x(), x.y(), 0.0}; }

ObstacleSpec plane(Eigen::Vector2d point, Eigen::Vector2d normal) {
  PlaneObstacle o;
  o.point = lift(point);
  o.normal = lift(normal.normalized());
  return {"obstacle", o};
}

ObstacleSpec circle(Eigen::Vector2d center, double radius) {
  CircleObstacle o;
  o.center = lift(center);
  o.radius = radius;
  return {"obstacle", o};
}

ObstacleSpec profile(std::vector<Eigen::Vector2d> points, bool body_on_left) {
  ProfileObstacle o;
  for (const auto& x : points) o.points.push_back(lift(x));
  o.body_on_left = body_on_left;
  return {"obstacle", o};
}

Eigen::Vector2d point_of(const ObstacleSpec& o) { return o.as<PlaneObstacle>()->point.head<2>(); }
Eigen::Vector2d center_of(const ObstacleSpec& o) { return o.as<CircleObstacle>()->center.head<2>(); }

}  // namespace

TEST_CASE("an inclined plane measures the gap along its normal", "[unit][obstacle]") {
  const ObstacleSpec o = plane({1, 2}, {-1, 1});
  const Eigen::Vector2d x(0.5, 3.0);
  const auto p = project(o, x);
  CHECK(p.gap == Approx((x - point_of(o)).dot(Eigen::Vector2d(-1, 1).normalized())));
  CHECK(p.normal.head<2>().isApprox(Eigen::Vector2d(-1, 1).normalized()));
  CHECK(detail::surface_coordinate(o, x, {}) == Approx((x - point_of(o)).dot(Eigen::Vector2d(1, 1).normalized())));
}

TEST_CASE("a circle: gap |x − c| − r along the radius, outside positive", "[unit][obstacle]") {
  const ObstacleSpec o = circle({1, -2}, 0.5);
  for (const Eigen::Vector2d& x : {Eigen::Vector2d(1, -1), Eigen::Vector2d(2, -2.5), Eigen::Vector2d(1.1, -2.2)}) {
    const auto p = project(o, x);
    CHECK(p.gap == Approx((x - center_of(o)).norm() - 0.5));
    CHECK(p.normal.head<2>().isApprox((x - center_of(o)).normalized()));
  }
  // Arc length from the origin direction (up), increasing clockwise (along (n_y, −n_x)).
  const double quarter = detail::surface_coordinate(o, Eigen::Vector2d(2, -2), Eigen::Vector2d::UnitY());
  CHECK(quarter == Approx(0.5 * M_PI / 2));
  CHECK(detail::obstacle_curvature(o) == 2.0);
}

TEST_CASE("a profile: segments, extended ends and vertices", "[unit][obstacle]") {
  // A V: down from (−1, 1) to (0, 0), up to (1, 1); the body above it (on the left walking
  // from the first point to the last).
  const ObstacleSpec v = profile({{-1, 1}, {0, 0}, {1, 1}}, true);
  SECTION("a point above a segment: its distance to the segment's line") {
    const auto p = project(v, Eigen::Vector2d(0.5, 1.5));
    CHECK(p.gap ==
          Approx((Eigen::Vector2d(0.5, 1.5) - Eigen::Vector2d(0, 0)).dot(Eigen::Vector2d(-1, 1).normalized())));
    CHECK(p.normal.head<2>().isApprox(Eigen::Vector2d(-1, 1).normalized()));
  }
  SECTION("beyond the last point the last segment goes on") {
    const auto p = project(v, Eigen::Vector2d(5, 5.5));
    CHECK(p.gap == Approx(0.5 / std::sqrt(2.0)));
  }
  SECTION("below the vertex, inside the obstacle: negative, normal from the vertex") {
    const auto p = project(v, Eigen::Vector2d(0, -0.3));
    CHECK(p.gap == Approx(-0.3));
    CHECK(p.normal.head<2>().isApprox(Eigen::Vector2d(0, 1)));
  }
  SECTION("the body on the right flips every sign") {
    const ObstacleSpec flipped = profile({{-1, 1}, {0, 0}, {1, 1}}, false);
    CHECK(project(flipped, Eigen::Vector2d(0.5, 1.5)).gap == Approx(-project(v, Eigen::Vector2d(0.5, 1.5)).gap));
  }
  SECTION("a roof: near its convex ridge the closest point is the vertex") {
    const ObstacleSpec roof = profile({{-1, 0}, {0, 1}, {1, 0}}, true);  // body above: the ridge points at it
    const Eigen::Vector2d x(0.1, 1.5);
    const auto p = project(roof, x);
    CHECK(p.gap == Approx((x - Eigen::Vector2d(0, 1)).norm()));
    CHECK(p.normal.head<2>().isApprox((x - Eigen::Vector2d(0, 1)).normalized()));
  }
  SECTION("arc length from the first point") {
    CHECK(detail::surface_coordinate(v, Eigen::Vector2d(0.5, 0.5), {}) == Approx(1.5 * std::sqrt(2.0)));
  }
}

TEST_CASE("the normal is the gradient of the gap, for every obstacle type", "[unit][obstacle]") {
  const ObstacleSpec obstacles[] = {plane({0, 0}, {0.3, 1}), circle({0, -1}, 1),
                                    profile({{-2, 1}, {-0.5, 0.2}, {0.5, 0.1}, {2, 1.5}}, true),
                                    profile({{-1, 0}, {0, 1}, {1, 0}}, true)};
  const Eigen::Vector2d points[] = {{0.3, 0.7}, {-0.4, 0.9}, {1.2, 1.9}, {0.05, 1.4}};
  const double h = 1e-6;
  for (const ObstacleSpec& o : obstacles) {
    for (const Eigen::Vector2d& x : points) {
      CAPTURE(o.type(), x.transpose());
      const auto p = project(o, x);
      const Eigen::Vector2d gradient((project(o, Eigen::Vector2d(x + h * Eigen::Vector2d::UnitX())).gap -
                                      project(o, Eigen::Vector2d(x - h * Eigen::Vector2d::UnitX())).gap) /
                                         (2 * h),
                                     (project(o, Eigen::Vector2d(x + h * Eigen::Vector2d::UnitY())).gap -
                                      project(o, Eigen::Vector2d(x - h * Eigen::Vector2d::UnitY())).gap) /
                                         (2 * h));
      CHECK((gradient - p.normal.head<2>()).norm() < 1e-6);
      CHECK(p.normal.norm() == Approx(1.0));
    }
  }
}
