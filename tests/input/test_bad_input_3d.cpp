// Bad 3D input: each names its field or element, exits 2 from the CLI with one line on stderr,
// and writes nothing. Also the scene reader's order of complaints: an unknown key that is a
// misspelling of a missing one is named first.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "contactqp/errors.hpp"
#include "contactqp/model.hpp"
#include "contactqp/scene.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

// Two tetrahedra in a Gmsh 2.2 file that disagree in orientation — (1 2 3 4) positive, (1 2 3 5)
// negative, a tangled mesh that turning the volume as a whole cannot mend — with a face as a
// physical surface.
const char* kInvertedTet = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
2 1 "surface"
3 2 "body"
$EndPhysicalNames
$Nodes
5
1 0 0 0
2 1 0 0
3 0 1 0
4 0 0 1
5 0 0 -1
$EndNodes
$Elements
3
1 2 2 1 1 1 2 3
2 4 2 2 1 1 2 3 4
3 4 2 2 1 1 2 3 5
$EndElements
)";

// One well-shaped tetrahedron: a 3D mesh that a 2D scene must refuse.
const char* kOneTet = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
2 1 "surface"
3 2 "body"
$EndPhysicalNames
$Nodes
4
1 0 0 0
2 1 0 0
3 0 1 0
4 0 0 1
$EndNodes
$Elements
2
1 2 2 1 1 1 3 2
2 4 2 2 1 1 2 3 4
$EndElements
)";

std::vector<BadScene> bad_3d_scenes(const std::string& inverted_msh, const std::string& tet_msh) {
  auto patch = [](const std::string& p) { return patched_scene("scenes/hertz-sphere.json", p); };
  return {
      {patch(R"({"load": {"value": [null, -0.01]}})"), "load.value"},
      {patch(R"({"obstacle": {"normal": [0, 1]}})"), "obstacle.normal"},
      {patch(R"({"obstacle": {"point": [0, 0, 0, 1]}})"), "obstacle.point"},
      {patch(R"({"model": "plane_strain"})"), "body.shape = \"hemisphere\": a 3D shape"},
      {patch(R"({"body": {"shape": "half_disc"}})"), "body.shape = \"half_disc\": a 2D shape"},
      {patch(R"({"obstacle": {"type": "circle", "center": [0, 0, -1], "radius": 1, "point": null, "normal": null}})"),
       "obstacle.type = \"circle\": a 2D obstacle"},
      {patch(
           R"({"obstacle": {"type": "punch", "center": [0, 0, 0], "axis": [0, 0, 1], "radius": 0, "point": null, "normal": null}})"),
       "obstacle.radius = 0"},
      {patch(
           R"({"obstacle": {"type": "punch", "center": [0, 0, 0], "axis": [0, 0, 1], "radius": -2, "point": null, "normal": null}})"),
       "obstacle.radius = -2"},
      {patch(
           R"({"obstacle": {"type": "punch", "center": [0, 0, 0], "axis": [0, 0, 0], "radius": 1, "point": null, "normal": null}})"),
       "obstacle.axis"},
      {patch(
           R"({"obstacle": {"type": "cylinder", "point": [0, 0, -1], "axis": [1, 0, 0], "point": null, "normal": null}})"),
       "obstacle"},
      {patch(R"({"obstacle": {"type": "sphere", "center": [0.3, 0, -1], "radius": 1, "point": null, "normal": null}})"),
       "body.symmetry"},
      {patch(R"({"transform": {"rotate_degrees": 30}})"), "transform.axis"},
      {patch(R"({"transform": {"rotate_degrees": 30, "axis": [0, 0, 0]}})"), "transform.axis"},
      {patch(R"({"transform": {"rotate_degrees": 30, "axis": [1, 0]}})"), "transform.axis"},
      {patch(R"({"body": {"thickness": 2}})"), "body.thickness"},
      {patch(R"({"body": {"shape": "box", "width": 1, "height": 1, "radius": null}, "load": {"boundary": "top"}})"),
       "body.depth"},
      {patch(R"({"body": {"formulation": "mixed"}})"), "body.formulation"},
      {patch(R"({"load": {"boundary": "arc"}})"), "load.boundary = \"arc\": not a boundary of a hemisphere"},
      {patch(
           R"({"body": {"shape": "mesh", "file": ")" + inverted_msh +
           R"(", "radius": null, "mesh": null, "symmetry": false}, "contact": {"boundary": "surface"}, "load": {"boundary": "surface"}})"),
       "inverted"},
      {patched_scene(
           "scenes/hertz.json",
           R"({"body": {"shape": "mesh", "file": ")" + tet_msh +
               R"(", "radius": null, "mesh": null, "symmetry": false}, "contact": {"boundary": "surface"}, "load": {"boundary": "surface"}})"),
       "3D mesh"},
  };
}

}  // namespace

TEST_CASE("bad 3D input: exit 2, one line naming the field or element, nothing written", "[input][cli][3d]") {
  TemporaryDirectory directory;
  const std::string msh = directory.path("inverted.msh");
  std::ofstream(msh) << kInvertedTet;
  const std::string tet = directory.path("tet.msh");
  std::ofstream(tet) << kOneTet;
  int k = 0;
  for (const BadScene& bad : bad_3d_scenes(msh, tet)) {
    CAPTURE(bad.text, bad.names);
    const std::string scene = directory.path("scene" + std::to_string(k++) + ".json");
    std::ofstream(scene) << bad.text;
    const auto before = directory_listing(directory.path(""));
    const std::string outputs = " --json " + directory.path("out.json") + " --csv " + directory.path("out.csv") +
                                " --vtu " + directory.path("out.vtu");
    const CliRun run = run_cli("solve " + scene + outputs);
    CHECK(run.exit_status == 2);
    CHECK(run.err.find(bad.names) != std::string::npos);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    CHECK(directory_listing(directory.path("")) == before);
  }
}

TEST_CASE("an unknown key that misspells a missing one is named before the missing one", "[input][scene]") {
  // "materail" instead of "material": the message names materail and suggests material.
  const std::string text = R"({"materail": {"E": 1, "nu": 0.3}, "body": {"shape": "half_disc", "radius": 1,
      "mesh": {"size": 0.1, "contact_size": 0.01}}, "load": {"type": "displacement", "boundary": "top",
      "value": [null, -0.01]}, "obstacle": {"type": "plane", "point": [0, 0], "normal": [0, 1]}})";
  CHECK_THROWS_WITH(parse_scene(text),
                    Catch::Matchers::Contains("materail") && Catch::Matchers::Contains("did you mean \"material\""));
  // A key that is simply missing is still said to be missing.
  CHECK_THROWS_WITH(parse_scene(R"({"material": {"E": 1}})"), Catch::Matchers::Contains("material.nu is missing"));
}
