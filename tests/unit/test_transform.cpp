// The scene transform: a rotated scene gives the same force, half-width and peak pressure as
// the unrotated one (the acceptance asks 1e-6 relative), with its displacements rotated.
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>

#include "contactqp/post.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

TEST_CASE("rotation matrices are exact for quarter turns", "[unit][transform]") {
  TransformSpec t;
  t.rotate_degrees = -270;
  CHECK(t.rotation() == (Eigen::Matrix3d() << 0, -1, 0, 1, 0, 0, 0, 0, 1).finished());
  t.rotate_degrees = 30;
  CHECK((t.rotation() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d(std::sqrt(3.0) / 2, 0.5, 0)));
}

TEST_CASE("rotated() turns obstacles and load vectors, not prescribed components", "[unit][transform]") {
  Scene scene = parse_scene(patched_scene("scenes/block-on-circle.json", R"({"transform": {"rotate_degrees": 90},
      "load": [{"type": "displacement", "boundary": "top", "value": [null, -0.02]},
               {"type": "gravity", "density": 1, "g": [0, -1]}]})"),
                            source_path("scenes/x.json"));
  const Scene turned = rotated(scene);
  CHECK(turned.transform.is_identity());
  CHECK(turned.obstacles[0].as<CircleObstacle>()->center.isApprox(Eigen::Vector3d(1, 0, 0)));
  CHECK(turned.loads[1].as<GravityLoad>()->g.isApprox(Eigen::Vector3d(1, 0, 0)));
  CHECK(*turned.loads[0].as<DisplacementLoad>()->value[1] == -0.02);
}

TEST_CASE("Hertz turned by any angle: the same force, b and p0 within 1e-6", "[unit][transform][hertz]") {
  const SceneRun base = solve_scene("scenes/hertz.json");
  const double angle = GENERATE(30.0, 137.5, -90.0, 1e-3);
  CAPTURE(angle);
  const SceneRun turned =
      solve_scene("scenes/hertz.json", R"({"transform": {"rotate_degrees": )" + std::to_string(angle) + "}}");
  REQUIRE(turned.result.status == Status::Converged);
  CHECK(relative_error(turned.contact.total_force, base.contact.total_force) < 1e-6);
  CHECK(relative_error(turned.contact.half_width, base.contact.half_width) < 1e-6);
  CHECK(relative_error(turned.contact.max_pressure, base.contact.max_pressure) < 1e-6);
  // The whole displacement field is the unrotated one, turned.
  const Eigen::Matrix2d R = turned.model.rotation.topLeftCorner<2, 2>();
  const Eigen::VectorXd u0 = full_displacement(base.model, base.result.u);
  const Eigen::VectorXd u1 = full_displacement(turned.model, turned.result.u);
  double worst = 0;
  for (int k = 0; k < base.model.mesh.n_nodes(); ++k) {
    CHECK((turned.model.mesh.nodes[k].head<2>() - R * base.model.mesh.nodes[k].head<2>()).norm() < 1e-12);
    worst = std::max(worst, (u1.segment<2>(2 * k) - R * u0.segment<2>(2 * k)).norm());
  }
  CHECK(worst < 1e-6 * u0.cwiseAbs().maxCoeff());
  // The push needed is the same force, along the turned axis.
  CHECK((turned.reactions[0].force.head<2>() - R * base.reactions[0].force.head<2>()).norm() <
        1e-6 * base.reactions[0].force.norm());
}

TEST_CASE("a turned circle indenter with gravity and a point load: invariant too", "[unit][transform]") {
  const std::string patch = R"({"body": {"mesh": {"size": 0.4, "contact_size": 0.01}}, "contact": {"max_gap": 0.05},
      "load": [{"type": "displacement", "boundary": "top", "value": [null, -0.02]},
               {"type": "gravity", "density": 0.001, "g": [0, -1]},
               {"type": "point", "at": [0.5, 2.0], "value": [0.001, -0.002]}]})";
  const SceneRun base = solve_scene("scenes/block-on-circle.json", patch);
  nlohmann::json turned_scene = nlohmann::json::parse(patched_scene("scenes/block-on-circle.json", patch));
  turned_scene["transform"] = {{"rotate_degrees", -63.0}};
  const SceneRun turned = solve_scene(parse_scene(turned_scene.dump(), source_path("scenes/x.json")));
  REQUIRE(base.result.status == Status::Converged);
  REQUIRE(turned.result.status == Status::Converged);
  CHECK(relative_error(turned.contact.total_force, base.contact.total_force) < 1e-6);
  CHECK(relative_error(turned.contact.half_width, base.contact.half_width) < 1e-6);
  CHECK(relative_error(turned.contact.max_pressure, base.contact.max_pressure) < 1e-6);
}
