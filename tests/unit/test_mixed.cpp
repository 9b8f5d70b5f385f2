// The mixed (P2–P0, condensed) formulation for nearly incompressible plane strain: the scene
// rules and the stresses. Its element is tested with the others in test_element.cpp.
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>

#include "contactqp/model.hpp"
#include "contactqp/post.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

TEST_CASE("mixed: the scene rules", "[unit][scene][mixed]") {
  const std::string hertz = "scenes/hertz.json";
  // The order follows the formulation; 3-node triangles and plane stress are refused.
  CHECK(parse_scene(patched_scene(hertz, R"({"body": {"formulation": "mixed"}})")).body.mesh.order == 2);
  CHECK(parse_scene(patched_scene(hertz, R"({"body": {"formulation": "displacement"}})")).body.mesh.order == 1);
  CHECK_THROWS_WITH(parse_scene(patched_scene(hertz, R"({"body": {"formulation": "mixed", "mesh": {"order": 1}}})")),
                    Catch::Matchers::Contains("body.mesh.order = 1: must be 2 with \"formulation\": \"mixed\""));
  CHECK_THROWS_WITH(parse_scene(patched_scene(hertz, R"({"model": "plane_stress", "body": {"formulation": "mixed"}})")),
                    Catch::Matchers::Contains("body.formulation = \"mixed\": only for \"model\": \"plane_strain\""));
  CHECK_THROWS_WITH(parse_scene(patched_scene(hertz, R"({"body": {"formulation": "mixd"}})")),
                    Catch::Matchers::Contains("did you mean \"mixed\""));
  CHECK_THROWS_WITH(parse_scene(patched_scene(hertz, R"({"body": {"formulaton": "mixed"}})")),
                    Catch::Matchers::Contains("did you mean \"body.formulation\""));
  // A .geo is meshed with 6-node triangles for the mixed formulation.
  const Scene geo = parse_scene(patched_scene("scenes/hertz-gmsh.json", R"({"body": {"formulation": "mixed"}})"),
                                source_path("scenes/hertz-gmsh.json"));
  CHECK(geo.body.mesh.order == 2);
}

TEST_CASE("mixed: stresses are D_dev ε plus the element's mean stress", "[unit][mixed]") {
  // A uniformly compressed block (exact for both formulations): the same nodal stresses,
  // σzz = ν(σxx + σyy) included, from either.
  const std::string block = R"({"material": {"E": 3.0, "nu": 0.49},
      "body": {"shape": "rectangle", "width": 2.0, "height": 1.0, "symmetry": true,
               "mesh": {"size": 0.5, "contact_size": 0.25, "order": 2}},
      "load": {"type": "displacement", "boundary": "top", "value": [null, -0.01]},
      "obstacle": {"type": "plane", "point": [0, 0], "normal": [0, 1]}})";
  nlohmann::json mixed = nlohmann::json::parse(block);
  mixed["body"]["formulation"] = "mixed";
  const SceneRun a = solve_scene(parse_scene(block));
  const SceneRun b = solve_scene(parse_scene(mixed.dump()));
  const NodalStress sa = nodal_stresses(a.model, full_displacement(a.model, a.result.u));
  const NodalStress sb = nodal_stresses(b.model, full_displacement(b.model, b.result.u));
  const double scale = sa.yy.cwiseAbs().maxCoeff();
  CHECK((sa.xx - sb.xx).cwiseAbs().maxCoeff() <= 1e-6 * scale);
  CHECK((sa.yy - sb.yy).cwiseAbs().maxCoeff() <= 1e-6 * scale);
  CHECK((sa.zz - sb.zz).cwiseAbs().maxCoeff() <= 1e-6 * scale);
  CHECK(sb.yy.mean() == Approx(-3.0 / (1 - 0.49 * 0.49) * 0.01).epsilon(1e-6));
}
