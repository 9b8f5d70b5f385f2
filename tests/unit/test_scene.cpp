// Scene parsing: the shipped scenes, defaults, and the ρ syntax.
#include <catch2/catch.hpp>

#include "contactqp/errors.hpp"
#include "contactqp/scene.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

TEST_CASE("the shipped Hertz scenes parse with the documented values", "[unit][scene]") {
  const Scene scene = load_scene(source_path("scenes/hertz.json"));
  CHECK(scene.model == PlaneModel::PlaneStrain);
  CHECK(scene.material.E == 1.0);
  CHECK(scene.material.nu == 0.3);
  CHECK(scene.body.shape == "half_disc");
  CHECK(scene.body.radius == 1.0);
  CHECK(scene.body.symmetry);
  CHECK(scene.body.mesh.order == 1);
  CHECK(scene.body.mesh.grading == 0.1);
  REQUIRE(scene.loads.size() == 1);
  CHECK_FALSE(scene.loads[0].value[0].has_value());  // the cut slides freely sideways
  CHECK(*scene.loads[0].value[1] == -0.016);
  REQUIRE(scene.obstacles.size() == 1);
  CHECK(scene.obstacles[0].as<PlaneObstacle>()->normal == Eigen::Vector3d(0, 1, 0));
  CHECK(scene.contact.boundary == "arc");
  CHECK(scene.solver.backend == Backend::Uzawa);
  CHECK(scene.solver.tol == 1e-8);
  const Scene large = load_scene(source_path("scenes/hertz-large.json"));
  CHECK(large.body.mesh.size < scene.body.mesh.size);
}

TEST_CASE("the schema example of the issue parses as written", "[unit][scene]") {
  const Scene scene = parse_scene(R"({
    "model": "plane_strain",
    "material": {"E": 1.0, "nu": 0.3},
    "body": {"shape": "half_disc", "radius": 1.0, "symmetry": true,
             "mesh": {"size": 0.1, "contact_size": 0.002}},
    "load": {"type": "displacement", "boundary": "top", "value": [0.0, -0.01]},
    "obstacle": {"type": "plane", "point": [0.0, 0.0], "normal": [0.0, 1.0]},
    "solver": {"backend": "uzawa", "tol": 1e-8}
  })");
  CHECK(*scene.loads[0].value[0] == 0.0);
  CHECK(*scene.loads[0].value[1] == -0.01);
}

TEST_CASE("obstacle normals are normalised and sections may be lists", "[unit][scene]") {
  const Scene scene = parse_scene(R"({
    "material": {"E": 3.0, "nu": 0.2},
    "body": {"shape": "half_disc", "radius": 2.0, "mesh": {"size": 0.5, "contact_size": 0.05, "order": 2}},
    "load": [{"type": "displacement", "boundary": "top", "value": [0.0, -0.01]}],
    "obstacle": [{"type": "plane", "point": [0.0, -0.1], "normal": [0.0, 3.0]}],
    "contact": {"max_gap": 0.2}
  })");
  CHECK(scene.obstacles[0].as<PlaneObstacle>()->normal == Eigen::Vector3d(0, 1, 0));
  CHECK(scene.body.mesh.order == 2);
  CHECK_FALSE(scene.body.symmetry);
  CHECK(*scene.contact.max_gap == 0.2);
}

TEST_CASE("rho: auto, absolute, or a fraction of rho_max", "[unit][scene]") {
  CHECK(parse_rho("auto", "--rho").rho_rule == UzawaOptions::RhoRule::Auto);
  const UzawaOptions absolute = parse_rho("0.004", "--rho");
  CHECK(absolute.rho_rule == UzawaOptions::RhoRule::Absolute);
  CHECK(absolute.rho == 0.004);
  const UzawaOptions fraction = parse_rho("2.2x", "--rho");
  CHECK(fraction.rho_rule == UzawaOptions::RhoRule::FractionOfMax);
  CHECK(fraction.rho == 2.2);
  for (const char* bad : {"", "x", "-1", "0", "0x", "fast", "1e400", "1.5xx", "nan"})
    CHECK_THROWS_WITH(parse_rho(bad, "--rho"), Catch::Matchers::StartsWith("--rho = "));
}
