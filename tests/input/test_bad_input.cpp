// Bad input: each names its field (and value), exits 2 from the CLI with one line on stderr,
// and never leaves an output file behind or truncates an existing one.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "contactqp/errors.hpp"
#include "contactqp/scene.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

struct BadScene {
  std::string text;    // a whole scene
  std::string names;   // what the one-line message must contain
};

std::vector<BadScene> bad_scenes() {
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
      {patch(R"({"load": {"type": "force"}})"), "load.type"},
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
  };
}

}  // namespace

TEST_CASE("every bad scene names its field", "[input]") {
  for (const BadScene& bad : bad_scenes()) {
    CAPTURE(bad.text.substr(0, 200), bad.names);
    CHECK_THROWS_WITH(parse_scene(bad.text), Catch::Matchers::Contains(bad.names));
  }
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
  for (const BadScene& bad : bad_scenes()) {
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
      {"solve " + scene + " --backend ipot", "--backend"},
      {"solve " + scene + " --tol -1", "--tol"},
      {"solve " + scene + " --rho 0.5y", "--rho"},
      {"solve " + scene + " --max-iterations 0", "--max-iterations"},
      {"solve " + scene + " --max-elements 10", "--max-elements"},
      {"solve " + scene + " --backend-option nonsense", "--backend-option"},
      {"solve " + scene + " --backend ipopt --backend-option print_lvl=5 --json " + out, "print_lvl"},
      {"solve " + scene + " --backend nlopt --backend-option algorithm=LD_FAST --json " + out, "LD_LBFGS"},
      {"compare " + scene + " --backends uzawa,ipot --json " + out, "valid: uzawa, ipopt, nlopt"},
      {"compare " + scene + " --backends uzawa,uzawa --json " + out, "listed twice"},
      {"compare " + scene + " --backends , --json " + out, "--backends"},
      {"compare " + scene + " --tol 0 --json " + out, "--tol"},
      {"compare " + scene + " --json " + directory.path("no/such/dir/out.json"), "--json"},
      {"compare " + scene + " --backend-option nlopt.algorithm=LD_FAST --json " + out, "LD_FAST"},
      {"compare " + scene + " --backend-option max_iter=5 --json " + out, "backend option max_iter"},
      {"compare " + directory.path("missing.json"), "missing.json"},
      {"solve " + scene + " --unknown-flag", "unknown-flag"},
      {"solve", "scene"},
      {"frobnicate", "frobnicate"},
  };
  for (const Case& c : cases) {
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
