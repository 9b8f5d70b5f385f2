// Bad input: each names its field (and value), exits 2 from the CLI with one line on stderr,
// and never leaves an output file behind or truncates an existing one.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "contactqp/errors.hpp"
#include "contactqp/model.hpp"
#include "contactqp/scene.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

std::vector<BadScene> bad_2d_scenes() {
  auto patch = [](const char* p) { return patched_scene("scenes/hertz.json", p); };
  return {
      {"{\"material\": ", "is not valid JSON"},
      {"[1, 2]", "must be an object"},
      {patch(R"({"materail": {"E": 1, "nu": 0.3}})"), "materail"},
      {patch(R"({"material": {"E": 0}})"), "material.E = 0"},
      {patch(R"({"material": {"E": -5}})"), "material.E = -5"},
      {patch(R"({"material": {"E": "stiff"}})"), "material.E"},
      {patch(R"({"material": {"nu": 0.5}})"), "material.nu = 0.5"},
      {patch(R"({"material": {"nu": -1}})"), "material.nu = -1"},
      {patch(R"({"material": {"Young": 1}})"), "material.Young"},
      {patch(R"({"body": {"radius": 0}})"), "body.radius = 0"},
      {patch(R"({"body": {"radius": -1}})"), "body.radius = -1"},
      {patch(R"({"body": {"shape": "sphere"}})"), "body.shape"},
      {patch(R"({"body": {"mesh": {"size": 0}}})"), "body.mesh.size = 0"},
      {patch(R"({"body": {"mesh": {"contact_size": 0.5}}})"), "body.mesh.contact_size = 0.5"},
      {patch(R"({"body": {"mesh": {"contact_size": -0.1}}})"), "body.mesh.contact_size"},
      {patch(R"({"body": {"mesh": {"order": 3}}})"), "body.mesh.order = 3"},
      {patch(R"({"body": {"mesh": {"grading": 0}}})"), "body.mesh.grading = 0"},
      {patch(R"({"body": {"mesh": {"sise": 0.1}}})"), "body.mesh.sise"},
      {patch(R"({"body": {"symmetry": "yes"}})"), "body.symmetry"},
      {patch(R"({"load": {"boundary": "bottom"}})"), "load.boundary"},
      {patch(R"({"load": {"type": "moment"}})"), "load.type"},
      {patch(R"({"load": {"value": [0]}})"), "load.value"},
      {patch(R"({"load": {"value": [null, null]}})"), "load.value"},
      {patch(R"({"obstacle": {"normal": [0, 0]}})"), "obstacle.normal"},
      {patch(R"({"obstacle": {"type": "sphere"}})"), "obstacle.type"},
      {patch(R"({"obstacle": {"point": [0]}})"), "obstacle.point"},
      {patch(R"({"solver": {"backend": "ipot"}})"), "solver.backend"},
      {patch(R"({"solver": {"tol": 0}})"), "solver.tol = 0"},
      {patch(R"({"solver": {"tol": 2}})"), "solver.tol = 2"},
      {patch(R"({"solver": {"rho": "fast"}})"), "solver.rho"},
      {patch(R"({"solver": {"max_iterations": 1.5}})"), "solver.max_iterations"},
      {patch(R"({"solver": {"tolerance": 1e-6}})"), "solver.tolerance"},
      {patch(R"({"model": "plain_strain"})"), "model"},
      {patch(R"({"contact": {"max_gap": -1}})"), "contact.max_gap = -1"},
      {patch(R"({"material": null})"), "material"},
      {patch(R"({"load": {"value": [0.1, -0.01]}})"), "body.symmetry"},
      // Issue 8: shapes, Gmsh files, loads, obstacles, transform.
      {patch(R"({"body": {"shape": "mesh"}})"), "body.file"},
      {patch(R"({"body": {"shape": "mesh", "file": "disc.stl", "radius": null, "mesh": null}})"), "body.file"},
      {patch(R"({"body": {"shape": "mesh", "file": "no_such_disc.msh", "radius": null, "mesh": null}})"), "body.file"},
      {patch(R"({"body": {"shape": "rectangle", "width": 0, "height": 1, "radius": null}})"), "body.width = 0"},
      {patch(R"({"body": {"shape": "rectangle", "width": 1}})"), "body.height"},
      {patch(R"({"body": {"shape": "rectangel"}})"), "did you mean \"rectangle\""},
      {patch(
           R"({"body": {"shape": "rectangle", "width": 4, "height": 2, "radius": null}, "load": {"boundary": "arc"}})"),
       "load.boundary = \"arc\": not a boundary of a rectangle"},
      {patch(R"({"load": {"type": "pressure"}})"), "load.value"},
      {patch(R"({"load": {"type": "traction", "value": 3}})"), "load.value"},
      {patch(R"({"load": {"type": "gravity", "density": -1, "g": [0, -1], "boundary": null, "value": null}})"),
       "load.density = -1"},
      {patch(R"({"load": {"type": "point", "boundary": null, "value": [0, 1]}})"), "load"},
      {patch(R"({"load": {"type": "point", "boundary": null, "value": [0, 1], "point": "tip"}})"), "load.point"},
      {patch(
           R"({"load": {"type": "gravity", "density": 1, "g": [0, -1], "boundary": null, "value": null, "region": "body"}})"),
       "load.region"},
      {patch(R"({"load": {"type": "pressure", "value": 1, "at": [0, 0]}})"), "load.at"},
      {patch(R"({"obstacle": {"type": "circle", "center": [0, -1], "radius": 0, "point": null, "normal": null}})"),
       "obstacle.radius = 0"},
      {patch(R"({"obstacle": {"type": "circle", "center": [0, -1], "point": null, "normal": null}})"),
       "obstacle.radius"},
      {patch(
           R"({"obstacle": {"type": "profile", "points": [[0, 0]], "body_side": "left", "point": null, "normal": null}})"),
       "obstacle.points"},
      {patch(
           R"({"obstacle": {"type": "profile", "points": [[-1, 0], [-1, 0], [1, 0]], "body_side": "left", "point": null, "normal": null}})"),
       "obstacle.points[1]"},
      {patch(
           R"({"obstacle": {"type": "profile", "points": [[-1, 0], [1, 1], [1, -1], [-1, 1]], "body_side": "left", "point": null, "normal": null}})"),
       "crosses itself"},
      {patch(
           R"({"obstacle": {"type": "profile", "points": [[-1, 0], [1, 0]], "body_side": "up", "point": null, "normal": null}})"),
       "obstacle.body_side"},
      {patch(R"({"obstacle": {"type": "cirlce"}})"), "did you mean \"circle\""},
      {patch(R"({"obstacle": {"type": "circle", "center": [0.5, -1], "radius": 1, "point": null, "normal": null}})"),
       "body.symmetry"},
      {patch(R"({"load": {"type": "traction", "value": [0.1, -1]}})"), "body.symmetry"},
      {patch(R"({"transform": {"rotate_degrees": "thirty"}})"), "transform.rotate_degrees"},
      {patch(R"({"transform": {"rotate": 30}})"), "transform.rotate"},
      {patch(R"({"transform": {"rotate_degrees": 30, "translate": [1, 0]}})"), "transform.translate"},
      // Issue 7: every category once more — syntax, keys, types, ranges, the mixed formulation.
      {"{\"material\": {\"E\": 1e999, \"nu\": 0.3}}", "is not valid JSON: number overflow"},
      {"{\"material\": {\"E\": 1, \"nu\": 0.3},}", "is not valid JSON"},
      {"", "is not valid JSON"},
      {patch(R"({"body": {"formulation": "mixd"}})"),
       "body.formulation = \"mixd\": unknown formulation; valid: displacement, mixed; did you mean \"mixed\"?"},
      {patch(R"({"body": {"formulaton": "mixed"}})"), "did you mean \"body.formulation\""},
      {patch(R"({"body": {"formulation": "mixed", "mesh": {"order": 1}}})"), "body.mesh.order = 1"},
      {patch(R"({"model": "plane_stress", "body": {"formulation": "mixed"}})"), "body.formulation = \"mixed\""},
      {patch(R"({"body": {"formulation": 2}})"), "body.formulation = 2: must be a string"},
      {patch(R"({"body": {"thickness": 0}})"), "body.thickness = 0"},
      {patch(R"({"body": {"thickness": -1e-3}})"), "body.thickness = -0.001"},
      {patch(R"({"material": {"E": 1e308}})"), "material.E = 1e+308: overflows"},
      {patch(R"({"material": {"nu": "0.3"}})"), "material.nu = \"0.3\": must be a number, not a string"},
      {patch(R"({"material": {"nu": 0.7}})"), "material.nu = 0.7"},
      {patch(R"({"material": {"nu": -1.5}})"), "material.nu = -1.5"},
      {patch(R"({"body": {"radius": true}})"), "body.radius = true: must be a number"},
      {patch(R"({"body": {"mesh": {"size": -0.1}}})"), "body.mesh.size = -0.1"},
      {patch(R"({"body": {"mesh": {"contact_size": 0.2}}})"),
       "body.mesh.contact_size = 0.2: must not exceed body.mesh.size = 0.1"},
      {patch(R"({"body": {"radius": 0.05, "mesh": {"size": 0.1, "contact_size": 0.08}}})"),
       "must not exceed the body's radius = 0.05"},
      {patch(R"({"body": {"mesh": {"size_factor": 2}}})"), "body.mesh.size_factor is not a valid key"},
      {patch(R"({"body": {"mesh": "fine"}})"), "body.mesh = \"fine\": must be an object"},
      {patch(R"({"load": []})"), "load = []"},
      {patch(R"({"load": {"boundary": "to\np"}})"), "load.boundary = \"to\\np\""},
      {patch(R"({"obstacle": 5})"), "obstacle = 5: must be an object"},
      {patch(R"({"obstacle": {"normal": [0, "1"]}})"), "obstacle.normal[1]"},
      {patch(R"({"solver": {"rho": -1}})"), "solver.rho = -1"},
      {patch(R"({"solver": {"rho": "0x"}})"), "solver.rho = \"0x\""},
      {patch(R"({"solver": {"max_iterations": 0}})"), "solver.max_iterations = 0"},
      {patch(R"({"solver": {"options": [1]}})"), "solver.options"},
      {patch(R"({"contact": {"max_gap": "big"}})"), "contact.max_gap = \"big\""},
      {patch(R"({"contact": {"boundary": "rim"}})"), "contact.boundary = \"rim\""},
      {patch(R"({"transform": 30})"), "transform = 30: must be an object"},
      {patch(R"({"description": 5})"), "description = 5: must be a string"},
      // Adaptive runs (docs/adaptive.md).
      {patch(R"({"adapt": {"target": 0}})"), "adapt.target = 0: must lie in (0, 1)"},
      {patch(R"({"adapt": {"target": 1.5}})"), "adapt.target = 1.5"},
      {patch(R"({"adapt": {"max_dofs": 1000}})"), "adapt.target"},
      {patch(R"({"adapt": {"target": 0.01, "max_dofs": 0}})"), "adapt.max_dofs = 0"},
      {patch(R"({"adapt": {"target": 0.01, "max_cycles": 0}})"), "adapt.max_cycles = 0"},
      {patch(R"({"adapt": {"target": 0.01, "max_dof": 10}})"), "adapt.max_dof"},
      {patch(R"({"adapt": 0.01})"), "adapt = 0.01: must be an object"},
      {patch(R"({"adapt": {"target": 0.01}, "estimate": false})"), "estimate = false: an adaptive run"},
  };
}

}  // namespace

TEST_CASE("every bad scene names its field", "[input]") {
  for (const BadScene& bad : bad_2d_scenes()) {
    CAPTURE(bad.text.substr(0, 200), bad.names);
    CHECK_THROWS_WITH(parse_scene(bad.text), Catch::Matchers::Contains(bad.names));
  }
}

TEST_CASE("names a mesh body does not have are errors naming the field, with a hint", "[input][gmsh]") {
  const std::string disc = source_path("scenes/hertz_disc.geo");
  const std::string base = R"({"material": {"E": 1, "nu": 0.3}, "body": {"shape": "mesh", "file": ")" + disc + R"("},
      "obstacle": {"type": "plane", "point": [0, 0], "normal": [0, 1]}, )";
  struct Case {
    std::string rest, names;
  };
  const Case cases[] = {
      {R"("load": {"type": "displacement", "boundary": "topp", "value": [0, -0.01]}, "contact": {"boundary": "arc"}})",
       "load.boundary = \"topp\": not a physical curve of " + disc + "; valid: arc, top; did you mean \"top\"?"},
      {R"("load": {"type": "displacement", "boundary": "top", "value": [0, -0.01]}, "contact": {"boundary": "rim"}})",
       "contact.boundary"},
      {R"("load": [{"type": "displacement", "boundary": "top", "value": [0, -0.01]}, {"type": "gravity", "density": 1, "g": [0, -1], "region": "bdy"}], "contact": {"boundary": "arc"}})",
       "load[1].region = \"bdy\""},
      {R"("load": [{"type": "displacement", "boundary": "top", "value": [0, -0.01]}, {"type": "point", "point": "tip", "value": [0, -1]}], "contact": {"boundary": "arc"}})",
       "load[1].point = \"tip\": not a physical point"},
      // An empty name is checked like any other (it once reached the mesh lookup: "map::at").
      {R"("load": [{"type": "displacement", "boundary": "top", "value": [0, -0.01]}, {"type": "traction", "boundary": "", "value": [0, -1]}], "contact": {"boundary": "arc"}})",
       "load[1].boundary = \"\": not a physical curve"},
      {R"("load": {"type": "displacement", "boundary": "top", "value": [0, -0.01]}})", "contact.boundary is missing"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.rest);
    CHECK_THROWS_WITH(build_model(parse_scene(base + c.rest)), Catch::Matchers::Contains(c.names));
  }
  nlohmann::json symmetric = nlohmann::json::parse(
      base +
      R"("load": {"type": "displacement", "boundary": "top", "value": [null, -0.01]}, "contact": {"boundary": "arc"}})");
  symmetric["body"]["symmetry"] = true;
  CHECK_THROWS_WITH(build_model(parse_scene(symmetric.dump())),
                    Catch::Matchers::Contains("no physical curve named \"symmetry\""));
}

TEST_CASE("misspelled keys come with the nearest valid one", "[input]") {
  CHECK_THROWS_WITH(parse_scene(patched_scene("scenes/hertz.json", R"({"solver": {"tolerance": 1e-6}})")),
                    Catch::Matchers::Contains("did you mean \"solver.tol\""));
  CHECK_THROWS_WITH(parse_scene(patched_scene("scenes/hertz.json", R"({"materail": {"E": 1, "nu": 0.3}})")),
                    Catch::Matchers::Contains("did you mean \"material\""));
  CHECK_THROWS_WITH(parse_scene(patched_scene("scenes/hertz.json", R"({"body": {"mesh": {"contact_sise": 0.01}}})")),
                    Catch::Matchers::Contains("did you mean \"body.mesh.contact_size\""));
}

TEST_CASE("the CLI exits 2 with one line and writes nothing on bad input", "[input][cli]") {
  TemporaryDirectory directory;
  const std::string out = directory.path("out.json");
  for (const BadScene& bad : bad_2d_scenes()) {
    CAPTURE(bad.names);
    const std::string scene = directory.path("bad.json");
    std::ofstream(scene) << bad.text;
    const CliRun run = run_cli("solve " + scene + " --json " + out);
    CHECK(run.exit_status == 2);
    CHECK(run.err.find(bad.names) != std::string::npos);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    CHECK_FALSE(std::filesystem::exists(out));
  }
}

TEST_CASE("the CLI rejects missing files, bad options and unwritable outputs", "[input][cli]") {
  TemporaryDirectory directory;
  const std::string scene = source_path("scenes/hertz.json");
  const std::string out = directory.path("out.json");
  struct Case {
    std::string arguments, names;
  };
  const Case cases[] = {
      {"solve " + directory.path("missing.json"), "missing.json"},
      {"solve " + directory.path(""), "is a directory"},
      {"solve " + scene + " --json " + directory.path("no/such/dir/out.json"), "--json"},
      {"solve " + scene + " --csv " + directory.path("no/such/dir/p.csv"), "--csv"},
      {"solve " + scene + " --vtu " + directory.path("no/such/dir/out.vtu"), "--vtu"},
      {"solve " + scene + " --backend ipot", "--backend"},
      {"solve " + scene + " --tol -1", "--tol"},
      {"solve " + scene + " --rho 0.5y", "--rho"},
      {"solve " + scene + " --max-iterations 0", "--max-iterations"},
      {"solve " + scene + " --max-elements 10", "--max-elements"},
      {"solve " + scene + " --backend-option nonsense", "--backend-option"},
      {"solve " + scene + " --backend ipopt --backend-option print_lvl=5 --json " + out, "print_lvl"},
      {"solve " + scene + " --backend nlopt --backend-option algorithm=LD_FAST --json " + out, "LD_LBFGS"},
      {"compare " + scene + " --backends uzawa,ipot --json " + out,
       "--backends = \"ipot\": unknown backend; valid: uzawa"},
      {"compare " + scene + " --backends uzawa,uzawa --json " + out, "listed twice"},
      {"compare " + scene + " --backends , --json " + out, "--backends"},
      {"compare " + scene + " --tol 0 --json " + out, "--tol"},
      {"compare " + scene + " --json " + directory.path("no/such/dir/out.json"), "--json"},
      {"compare " + scene + " --backend-option nlopt.algorithm=LD_FAST --json " + out, "LD_FAST"},
      {"compare " + scene + " --backend-option max_iter=5 --json " + out, "backend option max_iter"},
      {"compare " + directory.path("missing.json"), "missing.json"},
      {"solve " + scene + " --adapt 2", "--adapt = 2"},
      {"solve " + scene + " --adapt 0", "--adapt = 0"},
      {"solve " + scene + " --max-dofs 1000", "--max-dofs = 1000: is the budget of an adaptive run"},
      {"solve " + scene + " --adapt 0.01 --max-dofs -5", "--max-dofs = -5"},
      {"solve " + scene + " --adapt 0.01 --no-estimate", "estimate = false"},
      {"solve " + source_path("scenes/pin-on-plane.json") + " --adapt 0.1", "adapt needs a generated body"},
      {"solve " + scene + " --unknown-flag", "unknown-flag"},
      {"solve", "scene"},
      {"frobnicate", "frobnicate"},
  };
  for (const Case& c : cases) {
    // Ipopt and NLopt are optional at configure time: their rows need them built in.
    if ((!backend_available(Backend::Ipopt) && c.arguments.find("ipopt") != std::string::npos) ||
        (!backend_available(Backend::Nlopt) && c.arguments.find("nlopt") != std::string::npos))
      continue;
    CAPTURE(c.arguments);
    const CliRun run = run_cli(c.arguments);
    CHECK(run.exit_status == 2);
    CHECK(run.err.find(c.names) != std::string::npos);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    CHECK(run.out.empty());
    CHECK_FALSE(std::filesystem::exists(out));
  }
}

TEST_CASE("an existing result file is not truncated by a failed run", "[input][cli]") {
  TemporaryDirectory directory;
  const std::string out = directory.path("out.json");
  std::ofstream(out) << "previous result";
  const std::string scene = directory.path("bad.json");
  std::ofstream(scene) << patched_scene("scenes/hertz.json", R"({"material": {"E": -1}})");
  CHECK(run_cli("solve " + scene + " --json " + out).exit_status == 2);
  CHECK(read_text(out) == "previous result");
}

TEST_CASE("every kind of bad input, with every output option: exit 2, one line naming it, outputs untouched",
          "[input][cli][gmsh]") {
  TemporaryDirectory directory;
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(directory.path(name), std::ios::binary) << text;
    return directory.path(name);
  };
  // Gmsh files: a good one from the gmsh program, and broken ones.
  const std::string good = directory.path("good.msh");
  REQUIRE(
      std::system(("gmsh " + source_path("scenes/hertz_disc.geo") + " -2 -format msh22 -o " + good + " >/dev/null 2>&1")
                      .c_str()) == 0);
  const std::string good_text = read_text(good);
  write("garbage.msh", "garbage, not a mesh\n");
  write("truncated.msh", good_text.substr(0, good_text.size() / 3));
  write("empty.msh", "");
  write("random.msh", std::string("\x8f\x01\xff$Nodes\n\0\x7f", 12) + std::string(200, '\xee'));
  std::string version = good_text;
  version.replace(version.find("2.2 0 8"), 7, "9.9 0 8");
  write("version.msh", version);
  write("nan.msh",
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 nan 0 0\n3 0 1 0\n$EndNodes\n"
        "$Elements\n1\n1 2 2 1 1 1 2 3\n$EndElements\n");
  write("syntax.geo", "Point(1) = {0, 0, 0\n");
  std::filesystem::create_directory(directory.path("folder.msh"));

  auto mesh_scene = [&](const std::string& file, const std::string& extra = "") {
    nlohmann::json scene = nlohmann::json::parse(patched_scene("scenes/hertz-gmsh.json", extra.empty() ? "{}" : extra));
    scene["body"]["file"] = file;
    return write("scene-" + std::to_string(std::hash<std::string>()(file + extra)) + ".json", scene.dump());
  };
  auto scene = [&](const std::string& patch) {
    return write("scene-" + std::to_string(std::hash<std::string>()(patch)) + ".json",
                 patched_scene("scenes/hertz.json", patch));
  };
  const std::string hertz = scene("{}");

  const std::string json_out = write("out.json", "previous json"), csv_out = write("out.csv", "previous csv"),
                    vtu_out = write("out.vtu", "previous vtu"), compare_out = write("compare.json", "previous compare");
  struct Case {
    std::string arguments;  // after "solve": the scene and options
    std::string names;      // what the one line must contain
    // The outputs asked for: the files above, unless a case is about one of them.
    std::string json = "", csv = "", vtu = "";
  };
  const std::vector<Case> cases = {
      // The scene file itself.
      {write("syntax.json", "{\"material\": {\"E\": 1,"), "syntax.json is not valid JSON"},
      {directory.path("missing.json"), "missing.json cannot be read: No such file or directory"},
      {directory.path("folder.msh"), "folder.msh is a directory"},
      {scene(R"({"materail": {"E": 1}})"), "materail is not a valid key; did you mean \"material\"?"},
      {scene(R"({"material": {"E": "stiff"}})"), "material.E = \"stiff\": must be a number, not a string"},
      {scene(R"({"material": {"E": 0}})"), "material.E = 0: must be positive"},
      {scene(R"({"material": {"nu": 0.5}})"), "material.nu = 0.5: must lie in (-1, 0.5)"},
      {scene(R"({"body": {"radius": -2}})"), "body.radius = -2: must be positive"},
      {scene(R"({"body": {"mesh": {"size": 0}}})"), "body.mesh.size = 0: must be positive"},
      {scene(R"({"body": {"mesh": {"contact_size": 0.5}}})"),
       "body.mesh.contact_size = 0.5: must not exceed body.mesh.size"},
      {scene(R"({"material": {"E": 1e308}})"), "material.E = 1e+308"},
      {scene(R"({"material": {"E": 1e10}, "load": {"value": [null, -1e300]}, "obstacle": {"point": [0, -1e301]}})"),
       "load gives a load vector that overflows"},
      // A sideways load on the whole disc, which no row against the plane below can stop (the
      // disc without a load along x is solved: its free translation in x is undriven).
      {scene(
           R"({"body": {"symmetry": false}, "load": [{"type": "displacement", "boundary": "top", "value": [null, -0.016]},
                 {"type": "traction", "boundary": "top", "value": [0.01, 0]}]})"),
       "load leaves the body free to move rigidly (translation in x)"},
      {scene(R"({"material": {"E": 1e-320}})"), "the stiffness matrix underflows double precision"},
      {scene(R"({"load": {"value": [null, -1e-300]}})"), "load gives a load vector that underflows"},
      {scene(R"({"body": {"thickness": 1e308}})"),
       "material.E = 1 (body.thickness = 1e+308): the stiffness matrix overflows"},
      {write("deep.json", std::string(100000, '[') + std::string(100000, ']')),
       "deep.json is not a scene: arrays and objects nested deeper than 64"},
      // Sizes the element estimate once let through to Gmsh, which then took all the memory: a
      // contact size far below the grading's first band (estimated at 1e5 triangles, not 5e9),
      // and sizes whose square underflows (the estimate was 0/0).
      {scene(R"({"body": {"mesh": {"contact_size": 1e-9}}})"), "body.mesh would have about"},
      {scene(R"({"body": {"mesh": {"size": 1e-300, "contact_size": 1e-300}}})"),
       "body.mesh would have unboundedly many triangles"},
      // An element limit, for a generated mesh and for a file.
      {hertz + " --max-elements 1000", "body.mesh would have about"},
      {mesh_scene("good.msh") + " --max-elements 100", "more than the limit of 100; raise --max-elements"},
      // Gmsh files: missing, a directory, broken, the wrong names, the wrong order.
      {mesh_scene("missing.msh"), "body.file = \"missing.msh\": no such file"},
      {mesh_scene("folder.msh"), "body.file = \"folder.msh\": no such file"},
      {mesh_scene("garbage.msh"), "garbage.msh is not a Gmsh mesh file"},
      {mesh_scene("truncated.msh"), "truncated.msh "},  // ends early, or declares more than it holds
      {mesh_scene("empty.msh"), "empty.msh is not a Gmsh mesh file"},
      {mesh_scene("random.msh"), "random.msh is not a Gmsh mesh file"},
      {mesh_scene("version.msh"), "version.msh has the format line \"9.9 0 8\""},
      {mesh_scene("nan.msh"), "nan.msh has a coordinate of node 2 = nan: not a finite number"},
      {mesh_scene("syntax.geo"), "syntax.geo could not be meshed by Gmsh"},
      {mesh_scene("good.msh", R"({"contact": {"boundary": "rim"}})"),
       "contact.boundary = \"rim\": not a physical curve of"},
      {mesh_scene("good.msh", R"({"load": {"boundary": "topp"}})"), "did you mean \"top\"?"},
      {mesh_scene("good.msh", R"({"body": {"formulation": "mixed"}})"),
       "body.formulation = \"mixed\": needs 6-node triangles"},
      // Outputs: a missing directory, a directory, the scene file, the same file twice.
      {hertz, "--json = " + directory.path("no/such/out.json") + ": directory", directory.path("no/such/out.json")},
      {hertz, "--csv = " + directory.path("no/such/p.csv") + ": directory", "", directory.path("no/such/p.csv")},
      {hertz, "--vtu = " + directory.path("no/such/o.vtu") + ": directory", "", "", directory.path("no/such/o.vtu")},
      {hertz, "--json = " + directory.path("folder.msh") + ": is a directory, not a file",
       directory.path("folder.msh")},
      {hertz, "--json = " + hertz + ": is the scene file", hertz},
      {hertz, "--csv = " + json_out + ": the same file as --json", "", json_out},
  };
  const std::vector<std::string> before = directory_listing(directory.path(""));
  int checked = 0;
  for (const Case& c : cases) {
    CAPTURE(c.arguments);
    const std::string json = c.json.empty() ? json_out : c.json, csv = c.csv.empty() ? csv_out : c.csv,
                      vtu = c.vtu.empty() ? vtu_out : c.vtu;
    const CliRun solve = run_cli("solve " + c.arguments + " --json " + json + " --csv " + csv + " --vtu " + vtu);
    CAPTURE(solve.err);
    CHECK(solve.exit_status == 2);
    CHECK(solve.err.rfind("contactqp: error: ", 0) == 0);
    CHECK(solve.err.find(c.names) != std::string::npos);
    CHECK(std::count(solve.err.begin(), solve.err.end(), '\n') == 1);
    CHECK(solve.out.empty());
    if (c.csv.empty() && c.vtu.empty()) {
      const CliRun compare = run_cli("compare " + c.arguments + " --json " + (c.json.empty() ? compare_out : c.json));
      CAPTURE(compare.err);
      CHECK(compare.exit_status == 2);
      CHECK(std::count(compare.err.begin(), compare.err.end(), '\n') == 1);
    }
    CHECK(read_text(json_out) == "previous json");
    CHECK(read_text(csv_out) == "previous csv");
    CHECK(read_text(vtu_out) == "previous vtu");
    CHECK(read_text(compare_out) == "previous compare");
    CHECK(directory_listing(directory.path("")) == before);
    ++checked;
  }
  CHECK(checked >= 30);
}

TEST_CASE("an unreadable scene or mesh file is bad input naming it", "[input][cli]") {
  if (::geteuid() == 0) {
    // chmod 000 does not stop root from reading; the cases above cover missing files and
    // directories in place of files, which fail the same way.
    WARN("running as root: the permission-denied case is skipped");
    return;
  }
  TemporaryDirectory directory;
  const std::string scene = directory.path("locked.json");
  std::ofstream(scene) << read_text(source_path("scenes/hertz.json"));
  std::filesystem::permissions(scene, std::filesystem::perms::none);
  const CliRun r = run_cli("solve " + scene);
  CHECK(r.exit_status == 2);
  CHECK(r.err.find("locked.json cannot be read: Permission denied") != std::string::npos);
}

TEST_CASE("raising --max-elements lets a mesh over the default limit through", "[input][cli]") {
  TemporaryDirectory directory;
  const std::string scene = source_path("scenes/hertz-order2.json");
  CHECK(run_cli("solve " + scene + " --max-elements 100").exit_status == 2);
  const CliRun r = run_cli("solve " + scene + " --max-elements 100000 --json " + directory.path("out.json"));
  CHECK(r.exit_status == 0);
  CHECK(std::filesystem::exists(directory.path("out.json")));
}
