// Gmsh is a plugin (src/mesh/gmsh_plugin.hpp): the program loads it, and its ~90 shared
// libraries, only when a run meshes with Gmsh. Checked on the CLI with the dynamic loader's own
// log (LD_DEBUG=files names every library it opens), against a run that does mesh with Gmsh.
#include <sys/wait.h>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>

#include "test_support.hpp"

using namespace contactqp::testing;

namespace {

struct LoaderLog {
  int exit_status = -1;
  std::string log;  // the loader's log and the program's stderr
};

// Runs the CLI with `arguments`, the loader logging the files it opens.
LoaderLog run_logging_loads(const std::string& arguments) {
  TemporaryDirectory directory;
  const std::string err = directory.path("stderr");
  const std::string command = "LD_DEBUG=files " + std::string(CONTACTQP_CLI) + " " + arguments + " >/dev/null 2>" + err;
  const int raw = std::system(command.c_str());
  LoaderLog run;
  run.exit_status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
  run.log = read_text(err);
  return run;
}

bool loads_gmsh(const LoaderLog& run) { return run.log.find("libgmsh.so") != std::string::npos; }

}  // namespace

TEST_CASE("Gmsh is loaded only by a run that meshes with it", "[unit][gmsh_plugin]") {
  TemporaryDirectory directory;
  SECTION("--version and a scene refused for a bad key do not load it") {
    const LoaderLog version = run_logging_loads("--version");
    CHECK(version.exit_status == 0);
    CHECK_FALSE(loads_gmsh(version));
    const std::string bad = directory.path("bad.json");
    std::ofstream(bad) << patched_scene("scenes/hertz.json", R"({"body": {"radiuss": 1}})");
    const LoaderLog refused = run_logging_loads("solve " + bad);
    CHECK(refused.exit_status == 2);
    CHECK_FALSE(loads_gmsh(refused));
  }
  SECTION("a body read from a .msh file does not load it; the generated half disc does") {
    const std::string msh = directory.path("body.msh");
    const LoaderLog mesh = run_logging_loads("mesh " + source_path("scenes/hertz.json") + " -o " + msh);
    REQUIRE(mesh.exit_status == 0);
    CHECK(loads_gmsh(mesh));  // the check can see Gmsh: writing a .msh is Gmsh's work
    const std::string scene = directory.path("from-msh.json");
    std::ofstream(scene) << patched_scene("scenes/hertz.json",
                                          R"({"body": {"shape": "mesh", "file": ")" + msh +
                                              R"(", "radius": null, "mesh": null, "symmetry": true},)"
                                              R"( "contact": {"boundary": "arc"}})");
    const LoaderLog from_msh = run_logging_loads("solve " + scene + " --backend active_set");
    CHECK(from_msh.exit_status == 0);
    CHECK_FALSE(loads_gmsh(from_msh));
    const LoaderLog generated =
        run_logging_loads("solve " + source_path("scenes/hertz.json") + " --backend active_set");
    CHECK(generated.exit_status == 0);
    CHECK(loads_gmsh(generated));
  }
}
