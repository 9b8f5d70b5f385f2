// The energy-error estimate's effectivity on the cycles of adaptive runs with quadratic elements
// (docs/estimate.md, "On adaptive meshes"): Boussinesq's flat punch and Hertz's sphere, 3D P2,
// from one element size everywhere as benchmarks/adaptive/study.py starts them. On quadratic
// elements the energies do not measure the error (faces penetrate between nodes), so the true
// error of each cycle is measured by interpolation against the run's last cycle:
// energy_distance() locates each of the last mesh's nodes in the cycle's mesh. The meshes are
// remeshed, not nested, so this also counts the interpolation of the cycle's solution onto the
// last mesh, small where that mesh is finer. The last two cycles are left out: the reference's
// own error is then not small against theirs. Writes adaptive_effectivity.csv and context.json.
//
//   ./build/bench_adaptive_effectivity [--out DIR] [--quick]
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "contactqp/estimate.hpp"
#include "contactqp/run.hpp"
#include "context.hpp"
#include "out_arguments.hpp"

using namespace contactqp;

namespace {

struct Family {
  const char* name;
  const char* scene;
  const char* mesh;  // the one size everywhere, no grading (study.py's start)
  double target;     // the adaptive target η / sqrt(2E), as study.py's
  long long max_dofs;
};

// `scene` with quadratic elements on one size, adapted until `target` or cycle `cycles`.
std::string adaptive_scene(const Family& family, int cycles) {
  char patch[512];
  std::snprintf(patch, sizeof patch,
                R"({"body": {"mesh": %s}, "adapt": {"target": %.17g, "max_dofs": %lld, "max_cycles": %d},
                    "solver": {"tol": 1e-10}})",
                family.mesh, family.target, family.max_dofs, cycles);
  return patch;
}

// The scene file with a JSON merge patch applied (RFC 7386).
Scene patched(const std::string& scene, const std::string& patch) {
  std::ifstream in(std::string(CONTACTQP_SOURCE_DIR) + "/" + scene);
  nlohmann::json document = nlohmann::json::parse(in);
  document.merge_patch(nlohmann::json::parse(patch));
  return parse_scene(document.dump(), scene);
}

}  // namespace

int main(int argc, char** argv) {
  bench::OutArguments arguments;
  if (!bench::parse_out_arguments(argc, argv, "adaptive_effectivity", arguments)) return 2;
  try {
    const std::vector<Family> families =
        arguments.quick
            ? std::vector<Family>{{"punch-3d-p2", "scenes/punch.json",
                                   R"({"size": 4.0, "contact_size": 4.0, "grading": null, "order": 2})", 0.2, 20000}}
            : std::vector<Family>{
                  {"punch-3d-p2", "scenes/punch.json",
                   R"({"size": 2.0, "contact_size": 2.0, "grading": null, "order": 2})", 0.015, 250000},
                  {"hertz-3d-p2", "scenes/hertz-sphere.json",
                   R"({"size": 0.1, "contact_size": 0.1, "grading": null, "order": 2})", 0.005, 250000}};
    std::ofstream csv(bench::output_path(arguments.out, "adaptive_effectivity.csv"));
    csv << "scene,cycle,dofs,reference_dofs,estimate,relative,true_error,effectivity\n";
    std::printf(
        "| scene | cycle | DOFs | η/sqrt(2E) | true error | η | effectivity |\n|---|---|---|---|---|---|---|\n");
    for (const Family& family : families) {
      // The whole run first: its cycles, and its last one the reference.
      const RunReport whole = run_scene(patched(family.scene, adaptive_scene(family, 30)));
      if (!whole.adaptive) throw std::runtime_error(std::string(family.name) + ": not an adaptive run");
      const int cycles = static_cast<int>(whole.adaptive->cycles.size());
      for (int cycle = 1; cycle + 2 <= cycles; ++cycle) {
        // The run stopped after `cycle` solves is that cycle (the loop is deterministic).
        const RunReport r = run_scene(patched(family.scene, adaptive_scene(family, cycle)));
        const ErrorEstimate& e = *r.error_estimate;
        const double error = energy_distance(*r.model, r.result.u, *whole.model, *whole.qp, whole.result.u);
        char line[512];
        std::snprintf(line, sizeof line, "%s,%d,%lld,%lld,%.6e,%.6e,%.6e,%.4f\n", family.name, cycle, r.size.dofs,
                      whole.size.dofs, e.estimate, e.relative, error, e.estimate / error);
        csv << line;
        std::printf("| %s | %d | %lld | %.3g%% | %.3g | %.3g | %.2f |\n", family.name, cycle, r.size.dofs,
                    100 * e.relative, error, e.estimate, e.estimate / error);
        std::fflush(stdout);
      }
      std::printf("| %s | reference: cycle %d | %lld | %.3g%% | | | |\n", family.name, cycles, whole.size.dofs,
                  100 * whole.error_estimate->relative);
    }
    std::ofstream(bench::output_path(arguments.out, "context.json")) << bench::context_json("adaptive_effectivity");
  } catch (const std::exception& error) {
    std::cerr << "bench_adaptive_effectivity: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
