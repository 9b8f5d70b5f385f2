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
  const DisplacementLoad* push = scene.loads[0].as<DisplacementLoad>();
  REQUIRE(push);
  CHECK_FALSE(push->value[0].has_value());  // the cut slides freely sideways
  CHECK(*push->value[1] == -0.016);
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
  REQUIRE(scene.loads[0].is<DisplacementLoad>());
  CHECK(*scene.loads[0].as<DisplacementLoad>()->value[0] == 0.0);
  CHECK(*scene.loads[0].as<DisplacementLoad>()->value[1] == -0.01);
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

TEST_CASE("each load kind reads into its own type with its own fields", "[unit][scene]") {
  const Scene scene = parse_scene(patched_scene("scenes/hertz.json", R"({"body": {"symmetry": false}, "load": [
      {"type": "displacement", "boundary": "top", "value": [null, -0.016]},
      {"type": "traction", "boundary": "top", "value": [0.25, -2.0]},
      {"type": "pressure", "boundary": "arc", "value": 0.5},
      {"type": "gravity", "density": 3.0, "g": [0.0, -9.81]},
      {"type": "point", "at": [0.5, 0.25], "value": [1.5, -4.0]}]})"));
  REQUIRE(scene.loads.size() == 5);
  const std::vector<std::string> types = {"displacement", "traction", "pressure", "gravity", "point"};
  for (size_t l = 0; l < types.size(); ++l) {
    CHECK(scene.loads[l].type() == types[l]);
    CHECK(scene.loads[l].path == "load[" + std::to_string(l) + "]");
    CHECK(scene.loads[l].is_force() == (l != 0));
  }

  const DisplacementLoad* push = scene.loads[0].as<DisplacementLoad>();
  REQUIRE(push);
  CHECK(push->boundary == "top");
  CHECK_FALSE(push->value[0].has_value());
  CHECK(*push->value[1] == -0.016);
  CHECK_FALSE(push->value[2].has_value());  // 2D: two components
  CHECK(*scene.loads[0].boundary() == "top");

  const TractionLoad* traction = scene.loads[1].as<TractionLoad>();
  REQUIRE(traction);
  CHECK(traction->boundary == "top");
  CHECK(traction->traction == Eigen::Vector3d(0.25, -2.0, 0.0));

  const PressureLoad* pressure = scene.loads[2].as<PressureLoad>();
  REQUIRE(pressure);
  CHECK(pressure->boundary == "arc");
  CHECK(pressure->pressure == 0.5);
  CHECK(*scene.loads[2].boundary() == "arc");

  const GravityLoad* gravity = scene.loads[3].as<GravityLoad>();
  REQUIRE(gravity);
  CHECK(gravity->density == 3.0);
  CHECK(gravity->g == Eigen::Vector3d(0.0, -9.81, 0.0));
  CHECK(gravity->region.empty());  // the whole body
  CHECK(scene.loads[3].boundary() == nullptr);

  const PointLoad* point = scene.loads[4].as<PointLoad>();
  REQUIRE(point);
  REQUIRE(point->at);
  CHECK(*point->at == Eigen::Vector3d(0.5, 0.25, 0.0));
  CHECK(point->point.empty());
  CHECK(point->force == Eigen::Vector3d(1.5, -4.0, 0.0));
  CHECK(scene.loads[4].boundary() == nullptr);
  CHECK_FALSE(scene.loads[4].is<DisplacementLoad>());
}

TEST_CASE("a 3D load keeps its z component and a mesh body's named region and point", "[unit][scene]") {
  const Scene solid = parse_scene(patched_scene("scenes/hertz-sphere.json", R"({"load": [
      {"type": "displacement", "boundary": "top", "value": [null, null, -0.01]},
      {"type": "traction", "boundary": "top", "value": [0.0, 0.0, -0.5]}]})"));
  CHECK(*solid.loads[0].as<DisplacementLoad>()->value[2] == -0.01);
  CHECK(solid.loads[1].as<TractionLoad>()->traction == Eigen::Vector3d(0.0, 0.0, -0.5));
  const Scene strip = parse_scene(patched_scene("scenes/strip-liftoff.json", R"({"load": [
      {"type": "displacement", "boundary": "punch", "value": [0.0, -0.01]},
      {"type": "gravity", "density": 0.05, "g": [0.0, -9.81], "region": "strip"},
      {"type": "point", "point": "corner", "value": [0.0, -0.5]}]})"),
                                  source_path("scenes/x.json"));
  CHECK(strip.loads[1].as<GravityLoad>()->region == "strip");
  const PointLoad* corner = strip.loads[2].as<PointLoad>();
  REQUIRE(corner);
  CHECK(corner->point == "corner");  // build_model checks the mesh has it
  CHECK_FALSE(corner->at.has_value());
}

TEST_CASE("a field of another load kind is an unknown key of this one", "[unit][scene]") {
  const auto with = [](const std::string& load) {
    return patched_scene(
        "scenes/hertz.json",
        R"({"load": [{"type": "displacement", "boundary": "top", "value": [null, -0.016]}, )" + load + "]}");
  };
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"type": "displacement", "boundary": "top", "value": [null, -0.01], "pressure": 1})", "load[1].pressure"},
      {R"({"type": "displacement", "boundary": "top", "value": [null, -0.01], "density": 1})", "load[1].density"},
      {R"({"type": "traction", "boundary": "top", "value": [0, -1], "g": [0, -1]})", "load[1].g"},
      {R"({"type": "pressure", "boundary": "top", "value": 1, "point": "tip"})", "load[1].point"},
      {R"({"type": "gravity", "density": 1, "g": [0, -1], "boundary": "top"})", "load[1].boundary"},
      {R"({"type": "point", "at": [0, 1], "value": [0, -1], "region": "body"})", "load[1].region"},
  };
  for (const auto& [load, field] : cases) {
    CAPTURE(load);
    try {
      parse_scene(with(load));
      FAIL("accepted");
    } catch (const InputError& error) {
      CHECK(error.field() == field);
      // Before anything is missing; a key of another kind is named as such ("for \"type\": \"pressure\"").
      CHECK_THAT(std::string(error.what()), Catch::Matchers::StartsWith(field + " is not a valid key"));
    }
  }
}
