// Bad friction and load-step input in scenes (docs/friction.md): each names its field, and the CLI exits 2
// with one line and writes nothing.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "contactqp/run.hpp"
#include "contactqp/scene.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

// A push named for the steps, and a second load that the steps may name.
const char* const kNamedLoads =
    R"("load": [{"name": "push", "type": "displacement", "boundary": "top", "value": [null, -0.016]},
                {"name": "weight", "type": "gravity", "density": 1, "g": [0, -1]}])";

std::string with_loads(const std::string& rest) {
  return patched_scene("scenes/hertz.json", std::string("{") + kNamedLoads + ", " + rest + "}");
}

std::vector<BadScene> bad_friction_scenes() {
  auto patch = [](const char* p) { return patched_scene("scenes/hertz.json", p); };
  auto pair = [](const char* p) { return patched_scene("scenes/two-cylinders.json", p); };
  auto sphere = [](const char* p) { return patched_scene("scenes/hertz-sphere.json", p); };
  return {
      {patch(R"({"contact": {"friction": {"coefficient": -0.1}}})"),
       "contact.friction.coefficient = -0.1: must be ≥ 0"},
      {patch(R"({"contact": {"friction": {"threshold": -2}}})"), "contact.friction.threshold = -2: must be ≥ 0"},
      {patch(R"({"contact": {"friction": {"coefficient": 0.3, "threshold": 0.01}}})"),
       "contact.friction has both \"coefficient\""},
      {patch(R"({"contact": {"friction": {}}})"), "contact.friction needs \"coefficient\""},
      {patch(R"({"contact": {"friction": {"coeficient": 0.3}}})"), "did you mean \"contact.friction.coefficient\""},
      {patch(R"({"contact": {"friction": 0.3}})"), "contact.friction = 0.3: must be an object"},
      {patch(R"({"contact": {"friction": {"coefficient": "high"}}})"), "contact.friction.coefficient = \"high\""},
      {patch(R"({"obstacle": {"friction": {"coefficient": -1}}})"), "obstacle.friction.coefficient = -1"},
      {patch(R"({"contact": {"friction": {"coefficient": 0.3}}, "obstacle": {"friction": {"coefficient": 0.2}}})"),
       "obstacle.friction and contact.friction both apply to the rows against obstacle"},
      {patch(R"({"obstacle": [{"type": "plane", "point": [0, 0], "normal": [0, 1], "friction": {"coefficient": 0.3}},
                             {"type": "plane", "point": [0, -1], "normal": [0, 1], "friction": {"threshold": 0.1}}]})"),
       "obstacle[1].friction is Tresca's law and obstacle[0].friction Coulomb's: one friction law per scene"},
      {pair(R"({"contact": {"friction": {"coefficient": -0.3}}})"), "contact.friction.coefficient = -0.3"},
      {pair(R"({"contact": {"friction": {"threshold": 1, "coefficient": 1}}})"), "contact.friction has both"},
      // Load steps.
      {patch(R"({"steps": [{"factors": {"push": 1}}]})"), "steps scale named loads, and no load has a \"name\""},
      {with_loads(R"("steps": [{"factors": {"puhs": 1}}])"),
       "steps[0].factors.puhs is not a load: no load is named \"puhs\"; loads: push, weight; did you mean \"push\"?"},
      {with_loads(R"("steps": [{"factors": {"push": 1}}, {"factors": {"shear": 0.5}}])"),
       "steps[1].factors.shear is not a load"},
      {with_loads(R"("steps": [])"), "steps = []: must be a non-empty array"},
      {with_loads(R"("steps": {"factors": {"push": 1}})"), "steps = {"},
      {with_loads(R"("steps": [{"factors": {}}])"), "steps[0].factors = {}: must name at least one load"},
      {with_loads(R"("steps": [{"factors": {"push": "full"}}])"), "steps[0].factors.push = \"full\": must be a number"},
      {with_loads(R"("steps": [{"factor": {"push": 1}}])"), "did you mean \"steps[0].factors\""},
      {with_loads(R"("steps": [{"factors": {"push": 1}, "name": "first"}])"), "steps[0].name is not a valid key"},
      {with_loads(R"("steps": [5])"), "steps[0] = 5: must be an object"},
      {patch(R"({"load": {"name": ""}})"), "load.name = \"\": must be a non-empty name"},
      {patch(R"({"load": [{"name": "push", "type": "displacement", "boundary": "top", "value": [null, -0.016]},
                          {"name": "push", "type": "gravity", "density": 1, "g": [0, -1]}],
                 "steps": [{"factors": {"push": 1}}]})"),
       "load[1].name = \"push\": load[0] has this name too"},
      // A tangential load breaks the mirror symmetry the half model relies on.
      {patch(R"({"load": [{"name": "push", "type": "displacement", "boundary": "top", "value": [null, -0.016]},
                          {"name": "shear", "type": "displacement", "boundary": "top", "value": [0.001, null]}],
                 "contact": {"friction": {"coefficient": 0.3}},
                 "steps": [{"factors": {"push": 1}}, {"factors": {"shear": 1}}]})"),
       "body.symmetry = true: load[1] has ux = 0.001, which is not mirror-symmetric about x = 0"},
      // 3D keeps the one plane that contains the load: "symmetry": "y" (the half y ≥ 0).
      {sphere(R"({"body": {"symmetry": "y"},
                  "load": {"type": "displacement", "boundary": "top", "value": [null, 0.001, -0.01]}})"),
       "body.symmetry = \"y\": load has uy = 0.001, which is not mirror-symmetric about y = 0"},
      {sphere(R"({"load": {"type": "displacement", "boundary": "top", "value": [0.001, null, -0.01]}})"),
       "body.symmetry = true: load has ux = 0.001, which is not mirror-symmetric about x = 0"},
      {sphere(R"({"body": {"symmetry": "z"}})"), "body.symmetry = \"z\": unknown symmetry plane; valid: x, y"},
      {sphere(R"({"body": {"symmetry": 1}})"), "body.symmetry = 1: must be true, false, \"x\" or \"y\""},
      {patch(R"({"body": {"symmetry": "x"}})"), "body.symmetry = \"x\": must be true or false"},
  };
}

}  // namespace

TEST_CASE("bad friction and load steps name their field", "[input][friction]") {
  for (const BadScene& bad : bad_friction_scenes()) {
    CAPTURE(bad.text.substr(0, 300), bad.names);
    CHECK_THROWS_WITH(parse_scene(bad.text), Catch::Matchers::Contains(bad.names));
  }
}

TEST_CASE("bad friction and load steps exit 2 from the CLI and write nothing", "[input][friction][cli]") {
  TemporaryDirectory directory;
  const std::string out = directory.path("out.json"), csv = directory.path("p.csv"), vtu = directory.path("o.vtu");
  // One of each kind (friction, a misspelt key, steps, each symmetry): the test above checks every
  // message, and each CLI run costs a process start (0.5 s or more on a loaded machine).
  const std::vector<BadScene> all = bad_friction_scenes();
  for (const size_t k : {size_t{0}, size_t{4}, size_t{13}, size_t{24}, size_t{25}}) {
    const BadScene& bad = all.at(k);
    CAPTURE(bad.names);
    const std::string scene = directory.path("bad.json");
    std::ofstream(scene) << bad.text;
    const CliRun run = run_cli("solve " + scene + " --json " + out + " --csv " + csv + " --vtu " + vtu);
    CHECK(run.exit_status == 2);
    CHECK(run.err.find(bad.names) != std::string::npos);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    CHECK_FALSE(std::filesystem::exists(out));
    CHECK_FALSE(std::filesystem::exists(csv));
    CHECK_FALSE(std::filesystem::exists(vtu));
  }
}

TEST_CASE("load steps whose loads prescribe one DOF differently name the step", "[input][friction]") {
  // Two named displacements of the same boundary component, scaled apart by a step.
  const Scene scene = parse_scene(patched_scene("scenes/hertz.json", R"({"load": [
      {"name": "a", "type": "displacement", "boundary": "top", "value": [null, -0.016]},
      {"name": "b", "type": "displacement", "boundary": "top", "value": [null, -0.016]}],
      "steps": [{"factors": {"a": 1, "b": 1}}, {"factors": {"b": 0.5}}]})"));
  CHECK_THROWS_WITH(contactqp::run_scene(scene, RunOptions{}),
                    Catch::Matchers::Contains("steps[1] prescribes the node at"));
}

// (No quotes in the name: ctest passes it to Catch2 as a test spec, where they quote.)
TEST_CASE("symmetry y keeps the plane y = 0 only: a load along x is accepted", "[input][friction]") {
  const Scene scene = parse_scene(patched_scene("scenes/hertz-sphere.json", R"({"body": {"symmetry": "y"},
      "load": {"type": "displacement", "boundary": "top", "value": [0.001, null, -0.01]}})"));
  CHECK(symmetry_boundaries(scene.body, 3) == std::vector<std::string>{"symmetry_y"});
  CHECK(symmetry_copies(scene.body, 3) == 2);
  CHECK(symmetry_name(scene.body) == "y");
  const std::vector<std::string> names = boundary_names(scene.body);
  CHECK(std::count(names.begin(), names.end(), "symmetry_x") == 0);
  CHECK(std::count(names.begin(), names.end(), "symmetry_y") == 1);
  const Scene quarter = parse_scene(read_text(source_path("scenes/hertz-sphere.json")));
  CHECK(symmetry_copies(quarter.body, 3) == 4);
}
