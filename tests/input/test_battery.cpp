// The battery of bad input (issue 25's acceptance): what a new user gets wrong — misspelt,
// mis-nested and renamed keys, wrong types, NaN and huge values, empty arrays, missing and
// broken files, .msh files with the wrong contents, bad command lines — each through the
// contactqp binary with every output asked for: exit status 2, one line on stderr that names
// the field, file or element, nothing on stdout, and the directory exactly as it was (no
// result, no temporary file). Python's share is python/tests/test_battery.py. About 75 s of CPU
// (0.4 s a case, nearly all of it starting the binary): under the sanitizers, where a start costs
// several times more, CI leaves it to test_bad_input.cpp's 160 CLI cases and the fuzzers.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "test_support.hpp"

using namespace contactqp::testing;

namespace {

// The base every .msh case below breaks in one way.
const std::string kSquare = kUnitSquareMsh;

// The square on a rigid plane, pushed down by its top.
const std::string kSquareScene = R"({"model": "plane_strain", "material": {"E": 1, "nu": 0.3},
  "body": {"shape": "mesh", "file": "square.msh"},
  "load": {"type": "displacement", "boundary": "top", "value": [0, -0.01]},
  "obstacle": {"type": "plane", "point": [0, 0], "normal": [0, 1]},
  "contact": {"boundary": "bottom"}})";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

struct Case {
  std::string arguments;  // after "contactqp": the command, its files and options
  std::string names;      // what the one line must contain
};

}  // namespace

TEST_CASE("the battery of bad input: exit 2, one line naming it, nothing written", "[input][cli][battery]") {
  TemporaryDirectory directory;
  int n_files = 0;
  auto file = [&](const std::string& text, const std::string& extension = ".json") {
    const std::string name = "input" + std::to_string(++n_files) + extension;
    std::ofstream(directory.path(name), std::ios::binary) << text;
    return directory.path(name);
  };
  auto scene = [&](const std::string& patch, const std::string& base = "scenes/hertz.json") {
    return file(patched_scene(base, patch));
  };
  // A scene of the square with its mesh replaced by `msh` (and the scene patched).
  auto square = [&](const std::string& msh, const std::string& patch = "{}") {
    nlohmann::json text = nlohmann::json::parse(kSquareScene);
    text["body"]["file"] = file(msh, ".msh");
    text.merge_patch(nlohmann::json::parse(patch));  // a patch may name another file
    return file(text.dump());
  };
  const std::string hertz = scene("{}");
  const std::string sphere = scene("{}", "scenes/hertz-sphere.json");
  const std::string bodies = scene("{}", "scenes/roller-on-block.json");
  std::filesystem::create_directory(directory.path("folder"));

#if defined(__SANITIZE_ADDRESS__)
  WARN("skipped under AddressSanitizer: CI time (see the top of this file)");
  return;
#endif
  // The base cases are good input: what the battery breaks works when it is not broken.
  REQUIRE(run_cli("solve " + square(kSquare) + " --quiet").exit_status == 0);

  const std::vector<Case> cases = {
      // The file as JSON.
      {"solve " + file("\xEF\xBB\xBF{\"model\": \"plane_strain\"}"),
       "material is missing"},  // a byte-order mark is read
      {"solve " + file("{\"material\": {\"E\": 1}} trailing"), "is not valid JSON"},
      {"solve " + file("{\"material\": {\"E\": NaN, \"nu\": 0.3}}"), "is not valid JSON"},
      {"solve " + file("{\"material\": {\"E\": Infinity}}"), "is not valid JSON"},
      {"solve " + file("{'material': {}}"), "is not valid JSON"},
      {"solve " + file("// a scene\n{}"), "is not valid JSON"},
      {"solve " + file("null"), "must be an object"},
      {"solve " + file("\"hertz\""), "must be an object"},
      {"solve " + file("{}"), "material is missing"},
      {"solve " + file(std::string("{\"mod\xC3\x28l\": 1}")), "is not valid JSON"},  // invalid UTF-8
      {"solve " + file(patched_scene("scenes/hertz.json", "{}").insert(1, "\"model\": \"plane_strain\", ")),
       "model appears twice"},
      {"solve " + file(R"({"material": {"E": 1, "E": 2, "nu": 0.3}})"), "material.E appears twice"},
      // Keys: misspelt, renamed, mis-nested, in the wrong section.
      {"solve " + scene(R"({"material": {"nu": null, "poisson": 0.3}})"), "material.poisson is not a valid key"},
      {"solve " + scene(R"({"material": {"E": null, "young": 1}})"), "material.young is not a valid key"},
      {"solve " + scene(R"({"body": {"mesh": null, "size": 0.1, "contact_size": 0.002}})"),
       "body.contact_size is not a valid key; did you mean \"body.mesh.contact_size\"?"},
      {"solve " + scene(R"({"body": {"radius": null}, "radius": 1})"),
       "radius is not a valid key; did you mean \"body.radius\"?"},
      {"solve " + scene(R"({"material": null, "body": {"material": {"E": 1, "nu": 0.3}}})"),
       "body.material is not a valid key"},
      {"solve " + scene(R"({"solver": {"backend": null}, "backend": "uzawa"})"), "backend is not a valid key"},
      {"solve " + scene(R"({"obstacle": {"normal": null, "direction": [0, 1]}})"), "obstacle.direction"},
      {"solve " + scene(R"({"load": {"type": null, "kind": "displacement"}})"), "load.kind is not a valid key"},
      {"solve " + scene(R"({"body": {"Shape": "half_disc", "shape": null}})"),
       "body.Shape is not a valid key; did you mean \"body.shape\"?"},
      {"solve " + scene(R"({"contact": {"boundary": null, "boundaries": "arc"}})"), "contact.boundaries"},
      {"solve " + scene(R"({"transform": {"rotate": 30}})"), "transform.rotate"},
      {"solve " + scene(R"({"body": {"mesh": {"contact_size": null, "contact": 0.002}}})"),
       "body.mesh.contact is not a valid key"},
      {"solve " + scene(R"({"body": {"shape": "rectangle", "radius": 1}})"),
       "body.radius is not a valid key for \"shape\": \"rectangle\""},
      {"solve " + scene(R"({"obstacle": {"type": "circle"}})"),
       "obstacle.normal is not a valid key for \"type\": \"circle\""},
      {"solve " + scene(R"({"body": {"thickness": 1}})", "scenes/hertz-sphere.json"),
       "body.thickness is not a valid key in a 3D scene"},
      {"solve " + scene(R"({"bodies": [{"name": "a"}]})", "scenes/roller-on-block.json"),
       "bodies[0].material is missing"},
      // Types.
      {"solve " + scene(R"({"model": 2})"), "model = 2: must be a string"},
      {"solve " + scene(R"({"model": "Plane_Strain"})"), "model = \"Plane_Strain\": unknown model"},
      {"solve " + scene(R"({"model": "3d"})"), "model = \"3d\""},
      {"solve " + scene(R"({"material": [1, 0.3]})"), "material = [1,0.3]: must be an object"},
      {"solve " + scene(R"({"material": {"E": "1e9"}})"), "material.E = \"1e9\": must be a number, not a string"},
      {"solve " + scene(R"({"material": {"E": [1]}})"), "material.E = [1]: must be a number"},
      {"solve " + scene(R"({"material": {"E": {"value": 1}}})"), "material.E"},
      {"solve " + scene(R"({"material": {"nu": true}})"), "material.nu = true: must be a number"},
      {"solve " + scene(R"({"material": {"nu": "NaN"}})"), "material.nu = \"NaN\""},
      {"solve " + scene(R"({"body": {"shape": 1}})"), "body.shape = 1: must be a string"},
      {"solve " + scene(R"({"body": {"symmetry": "true"}})"), "body.symmetry = \"true\": must be true or false"},
      {"solve " + scene(R"({"body": {"symmetry": 1}})"), "body.symmetry = 1"},
      {"solve " + scene(R"({"body": {"mesh": {"order": "2"}}})"), "body.mesh.order = \"2\""},
      {"solve " + scene(R"({"body": {"mesh": {"order": 1.5}}})"), "body.mesh.order = 1.5: must be an integer"},
      {"solve " + scene(R"({"body": {"mesh": {"refinements": 1e10}}})"), "body.mesh.refinements"},
      {"solve " + scene(R"({"load": "top"})"), "load = \"top\": must be an object"},
      {"solve " + scene(R"({"load": [1]})"), "load[0] = 1: must be an object"},
      {"solve " + scene(R"({"load": {"value": "down"}})"), "load.value = \"down\""},
      {"solve " + scene(R"({"load": {"value": [null, "-0.016"]}})"), "load.value[1]"},
      {"solve " + scene(R"({"load": {"boundary": ["top"]}})"), "load.boundary = [\"top\"]: must be a string"},
      {"solve " + scene(R"({"obstacle": {"point": "origin"}})"), "obstacle.point = \"origin\""},
      {"solve " + scene(R"({"obstacle": [[0, 0]]})"), "obstacle[0] = [0,0]: must be an object"},
      {"solve " + scene(R"({"contact": "arc"})"), "contact = \"arc\": must be an object"},
      {"solve " + scene(R"({"solver": {"tol": "1e-8"}})"), "solver.tol = \"1e-8\""},
      {"solve " + scene(R"({"solver": {"max_iterations": "100"}})"), "solver.max_iterations"},
      {"solve " + scene(R"({"solver": {"options": {"print_level": true}}})"), "solver.options.print_level"},
      {"solve " + scene(R"({"solver": "uzawa"})"), "solver = \"uzawa\": must be an object"},
      {"solve " + scene(R"({"transform": {"rotate_degrees": null}})"), "transform.rotate_degrees is missing"},
      // Values: zero, negative, NaN-like, huge, tiny, out of range.
      {"solve " + scene(R"({"material": {"E": 0}})"), "material.E = 0: must be positive"},
      {"solve " + scene(R"({"material": {"E": -1e-300}})"), "material.E = -1e-300"},
      {"solve " + scene(R"({"material": {"E": 1e308}})"), "material.E = 1e+308: overflows"},
      {"solve " + scene(R"({"material": {"nu": 0.5}})"), "material.nu = 0.5: must lie in (-1, 0.5)"},
      {"solve " + scene(R"({"material": {"nu": 0.49999999999999999}})"), "material.nu = 0.5"},
      {"solve " + scene(R"({"material": {"nu": -1}})"), "material.nu = -1"},
      {"solve " + scene(R"({"body": {"radius": 0}})"), "body.radius = 0: must be positive"},
      {"solve " + scene(R"({"body": {"radius": 1e300}})"), "body.mesh would have"},
      {"solve " + scene(R"({"body": {"mesh": {"size": 1e-300, "contact_size": 1e-300}}})"), "body.mesh"},
      {"solve " + scene(R"({"body": {"mesh": {"grading": 2}}})"), "body.mesh.grading = 2"},
      {"solve " + scene(R"({"body": {"mesh": {"order": 3}}})"), "body.mesh.order = 3"},
      {"solve " + scene(R"({"body": {"mesh": {"refinements": 5}}})"), "body.mesh.refinements = 5"},
      {"solve " + scene(R"({"body": {"mesh": {"refinements": -1}}})"), "body.mesh.refinements = -1"},
      {"solve " + scene(R"({"body": {"thickness": 0}})"), "body.thickness = 0"},
      {"solve " + scene(R"({"load": {"value": [null, 1e308]}, "material": {"E": 1e300}})"), "load"},
      {"solve " + scene(R"({"load": {"value": [null, null]}})"), "load.value = [null, null]"},
      {"solve " + scene(R"({"load": {"value": [0, -0.016, 0]}})"), "load.value"},
      {"solve " + scene(R"({"load": []})"), "load = []: must hold at least one entry"},
      {"solve " + scene(R"({"obstacle": []})"), "obstacle = []"},
      {"solve " + scene(R"({"obstacle": {"normal": [0, 0]}})"), "obstacle.normal = [0,0]: must be a non-zero vector"},
      {"solve " + scene(R"({"obstacle": {"normal": [1e-320, 0]}})"), "obstacle.normal"},
      {"solve " + scene(R"({"obstacle": {"point": [0, 1e308]}})"), "obstacle"},
      {"solve " + scene(R"({"obstacle": {"type": "circle", "point": null, "normal": null, "center": [0, -1],
                                        "radius": -1}})"),
       "obstacle.radius = -1"},
      {"solve " + scene(R"({"obstacle": {"type": "profile", "point": null, "normal": null, "points": [],
                                        "body_side": "left"}})"),
       "obstacle.points = []"},
      {"solve " + scene(R"({"contact": {"max_gap": -0.1}})"), "contact.max_gap = -0.1"},
      {"solve " + scene(R"({"contact": {"boundary": "bottom"}})"), "contact.boundary = \"bottom\""},
      {"solve " + scene(R"({"load": {"boundary": ""}})"), "load.boundary = \"\""},
      {"solve " + scene(R"({"solver": {"tol": 0}})"), "solver.tol = 0"},
      {"solve " + scene(R"({"solver": {"tol": 1}})"), "solver.tol = 1"},
      {"solve " + scene(R"({"solver": {"max_iterations": -5}})"), "solver.max_iterations = -5"},
      {"solve " + scene(R"({"solver": {"max_iterations": 1e10}})"), "solver.max_iterations"},
      {"solve " + scene(R"({"solver": {"rho": 0}})"), "solver.rho = 0"},
      {"solve " + scene(R"({"solver": {"rho": "-2x"}})"), "solver.rho = \"-2x\""},
      {"solve " + scene(R"({"solver": {"backend": "Uzawa"}})"), "solver.backend = \"Uzawa\""},
      {"solve " + scene(R"({"solver": {"backend": ""}})"), "solver.backend"},
      {"solve " + scene(R"({"solver": {"linear_solver": "mumps"}})"), "solver.linear_solver = \"mumps\""},
      {"solve " + scene(R"({"transform": {"rotate_degrees": 1e308}})"),
       "transform.rotate_degrees = 1e+308: must lie in [-360, 360]"},
      // 3D and several bodies.
      {"solve " + scene(R"({"obstacle": {"normal": [0, 1]}})", "scenes/hertz-sphere.json"), "obstacle.normal"},
      {"solve " + scene(R"({"transform": {"rotate_degrees": 30}})", "scenes/hertz-sphere.json"),
       "transform.axis is missing"},
      {"solve " + scene(R"({"transform": {"rotate_degrees": 30, "axis": [0, 0, 0]}})", "scenes/hertz-sphere.json"),
       "transform.axis = [0,0,0]"},
      {"solve " + scene(R"({"body": {"shape": "rectangle"}})", "scenes/hertz-sphere.json"),
       "body.shape = \"rectangle\": a 2D shape"},
      {"solve " + scene(R"({"bodies": []})", "scenes/roller-on-block.json"), "bodies = []"},
      {"solve " + scene(R"({"contact": {"pair": ["roller.arc", "roller.top"]}})", "scenes/roller-on-block.json"),
       "contact.pair"},
      {"solve " + scene(R"({"contact": {"pair": ["roller.arc", "blok.top"]}})", "scenes/roller-on-block.json"),
       "did you mean \"block.top\""},
      {"solve " + scene(R"({"contact": {"pair": "roller.arc"}})", "scenes/roller-on-block.json"), "contact.pair"},
      {"solve " + scene(R"({"contact": null})", "scenes/roller-on-block.json"), "contact is missing"},
      {"solve " + scene(R"({"transform": {"rotate_degrees": 10}})", "scenes/roller-on-block.json"),
       "transform is not supported with \"bodies\""},
      // Mesh files: missing, not a mesh, broken, and meshes contactqp cannot use.
      {"solve " + square(kSquare, R"({"body": {"file": "nowhere.msh"}})"), "nowhere.msh"},
      // Gmsh runs a file that does not begin like a mesh as a script, whatever its name.
      {"solve " + square("Point(1) = {0, 0, 0};\nSystemCall \"touch " + directory.path("owned") + "\";\n"),
       "is not a Gmsh mesh file"},
      {"solve " + square(""), "is not a Gmsh mesh file"},
      {"solve " + square(replaced(kSquare, "2.2 0 8", "3.0 0 8")), "has the format line \"3.0 0 8\""},
      {"solve " + square(replaced(kSquare, "2.2 0 8", "2.2 0 4")), "has the format line \"2.2 0 4\""},
      {"solve " + square(replaced(kSquare, "2.2 0 8", "4.0 0 8")), "has the format line"},
      {"solve " + square(kSquare.substr(0, kSquare.size() / 2)), ".msh declares 4 nodes, more than"},
      {"solve " + square(replaced(kSquare, "2 1 0 0", "2 nan 0 0")), "node 2 = nan: not a finite number"},
      {"solve " + square(replaced(kSquare, "2 1 0 0", "2 inf 0 0")), "node 2 = inf: not a finite number"},
      {"solve " + square(replaced(kSquare, "3 1 1 0", "3 1e308 1e308 0")),
       "node 3 has a coordinate of 1e+308, beyond ±1e100"},
      {"solve " + square(replaced(kSquare, "4 0 1 0", "4 0 1 0.5")), "node 4 has z = 0.5"},
      {"solve " + square(replaced(kSquare, "6 2 2 5 1 1 3 4", "6 2 2 5 1 1 3 9")),
       "element 6 has node 9, which the mesh does not define"},
      {"solve " + square(replaced(kSquare, "$Nodes\n4\n", "$Nodes\n-4\n")), "the number of nodes"},
      {"solve " + square(replaced(kSquare, "$Nodes\n4\n", "$Nodes\n999999999999\n")),
       "declares 999999999999 nodes, more than"},
      {"solve " + square(replaced(kSquare, "$Elements\n6\n", "$Elements\n99\n")), ".msh declares 99 elements"},
      {"solve " + square(replaced(replaced(kSquare, "$Elements\n6\n", "$Elements\n4\n"),
                                  "5 2 2 5 1 1 2 3\n6 2 2 5 1 1 3 4\n", "")),
       "holds no triangles"},
      {"solve " + square(replaced(replaced(kSquare, "$Elements\n6\n", "$Elements\n5\n"),
                                  "5 2 2 5 1 1 2 3\n6 2 2 5 1 1 3 4", "5 3 2 5 1 1 2 3 4")),
       "holds 4-node quadrangle elements"},
      {"solve " + square(replaced(kSquare, "6 2 2 5 1 1 3 4", "6 2 2 5 1 1 3 1")), "element 6 is degenerate"},
      {"solve " + square(replaced(kSquare, "6 2 2 5 1 1 3 4", "6 2 2 5 1 1 2 4")), "element"},
      {"solve " + square(replaced(kSquare, "4 1 2 4 4 4 1", "4 1 2 4 4 4 7")),
       "physical curve \"left\" has a line element (tag 4) whose node 7 belongs to no triangle"},
      {"solve " + square(kSquare, R"({"contact": {"boundary": "Bottom"}})"),
       "contact.boundary = \"Bottom\": not a physical curve"},
      {"solve " + square(kSquare, R"({"load": {"boundary": "lid"}})"), "load.boundary = \"lid\""},
      {"solve " + square(kSquare, R"({"model": "solid", "load": {"value": [0, 0, -0.01]},
                                      "obstacle": {"point": [0, 0, 0], "normal": [0, 0, 1]}})"),
       ".msh holds a 2D mesh (tri3 elements), but \"model\": \"solid\" is 3D"},
      {"solve " + square(kSquare, R"({"body": {"mesh": {"order": 2}}})"), "body.mesh is not valid for a .msh file"},
      {"solve " + square(kSquare, R"({"load": {"type": "point", "boundary": null, "point": "tip",
                                                "value": [0, -1]}})"),
       "load.point = \"tip\""},
      {"solve " + square(kSquare, R"({"body": {"file": ")" + directory.path("folder") + R"("}})"), "body.file"},
      // The command line.
      {"solve " + hertz + " --tol nan", "--tol"},
      {"solve " + hertz + " --tol inf", "--tol"},
      {"solve " + hertz + " --tol 1e-400", "--tol"},
      {"solve " + hertz + " --tol 0.5.1", "--tol"},
      {"solve " + hertz + " --max-iterations 1e10", "--max-iterations"},
      {"solve " + hertz + " --max-iterations -1", "--max-iterations"},
      {"solve " + hertz + " --max-iterations 99999999999", "--max-iterations"},
      {"solve " + hertz + " --rho nan", "--rho"},
      {"solve " + hertz + " --rho 1e999", "--rho"},
      {"solve " + hertz + " --rho -0.5x", "--rho"},
      {"solve " + hertz + " --backend ''", "--backend"},
      {"solve " + hertz + " --backend uzawa,ipopt", "--backend"},
      {"solve " + hertz + " --ordering best", "--ordering"},
      {"solve " + hertz + " --linear-solver lu", "--linear-solver"},
      {"solve " + hertz + " --max-elements 0", "--max-elements"},
      {"solve " + hertz + " --max-elements abc", "--max-elements"},
      {"solve " + hertz + " --backend-option =5", "--backend-option"},
      {"solve " + hertz + " --backend-option rho=1", "rho"},
      {"solve " + hertz + " --json ''", "--json"},
      {"solve " + hertz + " --json " + directory.path("folder"), "--json"},
      {"solve " + hertz + " --csv " + directory.path("none/p.csv"), "--csv"},
      {"solve " + hertz + " --vtu " + hertz, "--vtu"},
      {"solve " + hertz + " " + hertz, "was not expected"},
      {"solve " + directory.path("folder"), "is a directory"},
      {"solve " + directory.path("absent.json"), "absent.json cannot be read"},
      {"solve", "scene"},
      {"", "subcommand"},
      {"solv " + hertz, "\"solv\" is not a command"},
      {"compare " + hertz + " --backends ''", "--backends"},
      {"compare " + hertz + " --backends uzawa,,ipopt", "--backends"},
      {"compare " + hertz + " --tol -1", "--tol"},
      {"mesh " + hertz + " -o " + directory.path("body.txt"), "-o"},
      {"mesh " + hertz, "-o"},
      {"mesh " + hertz + " -o " + directory.path("none/body.msh"), "-o"},
      {"mesh " + source_path("scenes/hertz-gmsh.json") + " -o " + directory.path("body.msh"), "body.shape"},
      {"mesh " + scene(R"({"body": {"mesh": {"size": 0}}})") + " -o " + directory.path("body.msh"),
       "body.mesh.size = 0"},
  };
  const std::vector<std::string> before = directory_listing(directory.path(""));
  const std::string outputs = " --json " + directory.path("out.json") + " --csv " + directory.path("out.csv") +
                              " --vtu " + directory.path("out.vtu");
  int checked = 0;
  for (const Case& c : cases) {
    const bool solve = c.arguments.rfind("solve ", 0) == 0 && c.arguments.find("--json") == std::string::npos &&
                       c.arguments.find("--csv") == std::string::npos && c.arguments.find("--vtu") == std::string::npos;
    const std::string command = c.arguments + (solve ? outputs : "");
    CAPTURE(command, c.names);
    const CliRun run = run_cli(command);
    CAPTURE(run.err);
    CHECK(run.exit_status == 2);
    CHECK(run.err.find(c.names) != std::string::npos);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    CHECK(run.out.empty());
    CHECK(directory_listing(directory.path("")) == before);
    ++checked;
  }
  INFO(checked << " cases");
  CHECK(checked >= 150);
}
