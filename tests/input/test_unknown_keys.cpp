// Unknown keys first (issue 25): wherever a scene holds a key its section does not have — at
// any depth, in any body of a "bodies" list, in any entry of a list of loads — that key is
// reported, with the nearest valid one, before any key is found missing. And the fuzzer's
// dictionary knows every key of the format (src/scene/scene_keys.cpp).
#include <catch2/catch.hpp>
#include <fstream>
#include <set>
#include <sstream>

#include "contactqp/errors.hpp"
#include "contactqp/scene.hpp"
#include "scene/scene_keys.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

struct RenamedKey {
  std::string scene;     // a shipped scene
  std::string patch;     // a JSON merge patch: renames a key (null removes the old one)
  std::string expected;  // the whole message
};

}  // namespace

TEST_CASE("an unknown key is reported before any missing key, at every depth", "[input]") {
  const RenamedKey cases[] = {
      // The case of the issue: a renamed material.nu.
      {"scenes/hertz.json", R"({"material": {"nu": null, "poisson": 0.3}})",
       "material.poisson is not a valid key; did you mean \"material.nu\"?"},
      {"scenes/hertz.json", R"({"material": {"nu": null, "Nu": 0.3}})",
       "material.Nu is not a valid key; did you mean \"material.nu\"?"},
      // A missing section elsewhere is still second: the unknown key inside "solver" comes first.
      {"scenes/hertz.json", R"({"body": null, "solver": {"tolerance": 1e-6}})",
       "solver.tolerance is not a valid key; did you mean \"solver.tol\"?"},
      {"scenes/hertz.json", R"({"material": {"E": null}, "obstacle": {"normal": null, "normale": [0, 1]}})",
       "obstacle.normale is not a valid key; did you mean \"obstacle.normal\"?"},
      // Two levels down, with a missing key beside it.
      {"scenes/hertz.json", R"({"body": {"mesh": {"size": null, "sizes": 0.1}}})",
       "body.mesh.sizes is not a valid key; did you mean \"body.mesh.size\"?"},
      // An entry of a list of loads.
      {"scenes/block-on-circle.json", R"({"load": [{"type": "displacement", "boundary": "top", "value": [0, -0.01]},
                                                   {"type": "gravity", "density": 1, "gravity": [0, -1]}]})",
       "load[1].gravity is not a valid key; did you mean \"load[1].g\"?"},
      // Every body of a two-body scene, its material and its loads.
      {"scenes/roller-on-block.json",
       R"({"bodies": [{"name": "roller", "shape": "half_disc", "radius": 1, "symmetry": true,
                       "mesh": {"size": 0.1, "contact_size": 0.002}, "material": {"E": 1, "nu": 0.3},
                       "load": {"type": "displacement", "boundary": "top", "value": [null, -0.016]}},
                      {"name": "block", "shape": "rectangle", "width": 8, "height": 4, "symmetry": true,
                       "offset": [0, -4], "mesh": {"size": 0.4, "contact_size": 0.002},
                       "material": {"E": 3, "poisson": 0.2},
                       "load": {"type": "displacement", "boundary": "bottom", "value": [null, 0]}}]})",
       "bodies[1].material.poisson is not a valid key"},
      {"scenes/roller-on-block.json",
       R"({"bodies": [{"name": "roller", "shape": "half_disc", "radius": 1, "symmetry": true,
                       "mesh": {"size": 0.1, "contact_size": 0.002}, "material": {"E": 1, "nu": 0.3},
                       "load": {"type": "displacement", "boundary": "top", "value": [null, -0.016]}},
                      {"name": "block", "shape": "rectangle", "width": 8, "symmetry": true,
                       "offset": [0, -4], "mesh": {"size": 0.4, "contact_size": 0.002},
                       "material": {"E": 3, "nu": 0.2},
                       "load": [{"type": "displacement", "boundary": "bottom", "value": [null, 0]},
                                {"type": "traction", "boundary": "right", "valeu": [1, 0]}]}]})",
       "bodies[1].load[1].valeu is not a valid key; did you mean \"bodies[1].load[1].value\"?"},
      {"scenes/roller-on-block.json", R"({"contact": {"pair": null, "pairs": ["roller.arc", "block.top"]}})",
       "contact.pairs is not a valid key; did you mean \"contact.pair\"?"},
      // A key of another variant of the section: said so, before the variant's own key is missing.
      {"scenes/hertz.json", R"({"body": {"shape": "rectangle", "radius": 1}})",
       "body.radius is not a valid key for \"shape\": \"rectangle\""},
      {"scenes/hertz.json", R"({"obstacle": {"type": "circle", "normal": null}})",
       "obstacle.point is not a valid key for \"type\": \"circle\""},
      {"scenes/hertz.json", R"({"body": {"mesh": {"size_factor": 2}}})",
       "body.mesh.size_factor is not a valid key for a generated shape"},
      // A key of the other dimension.
      {"scenes/punch.json", R"({"body": {"thickness": 2, "width": null}})",
       "body.thickness is not a valid key in a 3D scene (\"model\": \"solid\")"},
      {"scenes/hertz.json", R"({"transform": {"axis": [0, 0, 1]}})",
       "transform.axis is not a valid key in a 2D scene (\"model\": \"solid\" is 3D)"},
  };
  for (const RenamedKey& c : cases) {
    CAPTURE(c.scene, c.patch);
    CHECK_THROWS_WITH(parse_scene(patched_scene(c.scene, c.patch), source_path(c.scene)),
                      Catch::Matchers::StartsWith(c.expected));
  }
}

TEST_CASE("a missing key is still named when no key is unknown", "[input]") {
  CHECK_THROWS_WITH(parse_scene(patched_scene("scenes/hertz.json", R"({"material": {"nu": null}})")),
                    "material.nu is missing: it is required");
  CHECK_THROWS_WITH(
      parse_scene(patched_scene("scenes/hertz.json", R"({"body": {"shape": "rectangle", "radius": null}})")),
      "body.width is missing: it is required");
}

TEST_CASE("every shipped scene passes the key check", "[input]") {
  for (const char* name : {"block-on-circle", "disc-in-vgroove", "hertz-gmsh", "hertz-large", "hertz-order2",
                           "hertz-rotated", "hertz-sphere-large", "hertz-sphere", "hertz", "pin-on-plane", "punch",
                           "roller-on-block", "strip-liftoff", "two-cylinders", "two-spheres"}) {
    const std::string path = source_path("scenes/" + std::string(name) + ".json");
    CAPTURE(path);
    CHECK_NOTHROW(parse_scene(read_text(path), path));
  }
}

TEST_CASE("the fuzzer's dictionary holds every key and choice of the scene format", "[input]") {
  std::ifstream file(source_path("fuzz/scene.dict"));
  std::set<std::string> tokens;
  for (std::string line; std::getline(file, line);)
    if (!line.empty() && line.front() == '"') tokens.insert(line);
  std::string missing;
  for (const std::string& word : detail::scene_words())
    if (!tokens.count("\"\\\"" + word + "\\\"\"")) missing += "\"\\\"" + word + "\\\"\"\n";
  INFO("add these lines to fuzz/scene.dict:\n" << missing);
  CHECK(missing.empty());
}

TEST_CASE("the scene readers read only keys the format lists", "[input]") {
  // The table of scene_keys.cpp is the one list: a reader asking for another key is a
  // programming error, never an InputError a user could fix.
  const detail::Section* material = detail::section_at("bodies[3].material");
  REQUIRE(material != nullptr);
  CHECK(material == detail::section_at("material"));
  CHECK(detail::section_at("load[2]") == detail::section_at("bodies[0].load"));
  CHECK(detail::section_at("material.E") == nullptr);
  CHECK(detail::section_at("no_such_section") == nullptr);
}
