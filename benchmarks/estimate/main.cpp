// The energy-error estimate measured (docs/estimate.md): its effectivity on Hertz's cylinder (2D,
// P1 and P2) and sphere (3D, P1 and P2), two cylinders (a pair, P1 and P2) and Cattaneo-Mindlin's two
// cylinders (Coulomb, three load steps: the last step's error) over nested meshes against a
// finer mesh of the same scene, and
// its cost against the solve on shipped scenes. Writes effectivity.csv and cost.csv, with
// context.json beside them.
//
//   ./build/bench_estimate [--out DIR] [--quick]
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "contactqp/estimate.hpp"
#include "contactqp/run.hpp"
#include "context.hpp"
#include "out_arguments.hpp"

using namespace contactqp;

namespace {

// Level n of a scene: the same coarse Gmsh mesh (sizes and grading 2ⁿ smaller, `refinements` n)
// split n times, so that the levels are nested.
std::string hertz_level(bool sphere, int level, int order) {
  const double scale = std::ldexp(1.0, -level);
  char text[1024];
  if (sphere)
    std::snprintf(text, sizeof text, R"({"model": "solid", "material": {"E": 1.0, "nu": 0.3},
      "body": {"shape": "hemisphere", "radius": 1.0, "symmetry": true,
               "mesh": {"size": %.17g, "contact_size": %.17g, "grading": %.17g, "refinements": %d, "order": %d}},
      "load": {"type": "displacement", "boundary": "top", "value": [null, null, -0.01]},
      "obstacle": {"type": "plane", "point": [0.0, 0.0, 0.0], "normal": [0.0, 0.0, 1.0]},
      "solver": {"backend": "active_set", "tol": 1e-10}})",
                  0.4 * scale, 0.04 * scale, 0.6 * scale, level, order);
  else
    std::snprintf(text, sizeof text, R"({"model": "plane_strain", "material": {"E": 1.0, "nu": 0.3},
      "body": {"shape": "half_disc", "radius": 1.0, "symmetry": true,
               "mesh": {"size": %.17g, "contact_size": %.17g, "grading": %.17g, "refinements": %d, "order": %d}},
      "load": {"type": "displacement", "boundary": "top", "value": [null, -0.016]},
      "obstacle": {"type": "plane", "point": [0.0, 0.0], "normal": [0.0, 1.0]},
      "solver": {"backend": "active_set", "tol": 1e-11}})",
                  0.25 * scale, 0.025 * scale, 0.2 * scale, level, order);
  return text;
}

// scenes/two-cylinders.json (a pair: radius 1 on radius 2, E 1 and 2) on nested levels as above.
std::string two_cylinders_level(int level, int order) {
  const double scale = std::ldexp(1.0, -level);
  char text[2048];
  std::snprintf(text, sizeof text, R"({"model": "plane_strain",
    "bodies": [{"name": "roller", "shape": "half_disc", "radius": 1.0, "symmetry": true,
                "mesh": {"size": %.17g, "contact_size": %.17g, "grading": %.17g, "refinements": %d, "order": %d},
                "material": {"E": 1.0, "nu": 0.3},
                "load": {"type": "displacement", "boundary": "top", "value": [null, -0.016]}},
               {"name": "base", "shape": "half_disc", "radius": 2.0, "symmetry": true, "mirror": true,
                "mesh": {"size": %.17g, "contact_size": %.17g, "grading": %.17g, "refinements": %d, "order": %d},
                "material": {"E": 2.0, "nu": 0.25},
                "load": {"type": "displacement", "boundary": "top", "value": [null, 0.0]}}],
    "contact": {"pair": ["roller.arc", "base.arc"]},
    "solver": {"backend": "active_set", "tol": 1e-11}})",
                0.25 * scale, 0.025 * scale, 0.2 * scale, level, order, 0.5 * scale, 0.025 * scale, 0.2 * scale, level,
                order);
  return text;
}

// scenes/mindlin-cylinders.json (Coulomb, μ = 0.3: pressed, then sheared to Q/(μP) = 0.7 in two
// steps) on nested levels, graded to b/10 at the contact on level 0 (b = 0.002).
std::string mindlin_level(int level, int order) {
  const double scale = std::ldexp(1.0, -level);
  char mesh[256];
  std::snprintf(mesh, sizeof mesh,
                R"("mesh": {"size": %.17g, "contact_size": %.17g, "grading": %.17g, "refinements": %d, "order": %d})",
                0.25 * scale, 2e-4 * scale, 0.2 * scale, level, order);
  return std::string(R"({"model": "plane_strain",
    "bodies": [{"name": "upper", "shape": "half_disc", "radius": 1.0, )") +
         mesh + R"(, "material": {"E": 1.0, "nu": 0.3},
                "load": [{"name": "push", "type": "displacement", "boundary": "top", "value": [null, -2.5e-05]},
                         {"name": "shear", "type": "displacement", "boundary": "top", "value": [7.144e-06, null]}]},
               {"name": "lower", "shape": "half_disc", "radius": 1.0, "mirror": true, )" +
         mesh + R"(, "material": {"E": 1.0, "nu": 0.3},
                "load": {"type": "displacement", "boundary": "top", "value": [0.0, 0.0]}}],
    "contact": {"pair": ["upper.arc", "lower.arc"], "friction": {"coefficient": 0.3}},
    "steps": [{"factors": {"push": 1}}, {"factors": {"shear": 0.4183}}, {"factors": {"shear": 1}}],
    "solver": {"backend": "active_set", "tol": 1e-10}})";
}

enum class Kind { HalfDisc, Hemisphere, TwoCylinders, Mindlin };

std::string level_scene(Kind kind, int level, int order) {
  switch (kind) {
    case Kind::HalfDisc:
      return hertz_level(false, level, order);
    case Kind::Hemisphere:
      return hertz_level(true, level, order);
    case Kind::TwoCylinders:
      return two_cylinders_level(level, order);
    case Kind::Mindlin:
      return mindlin_level(level, order);
  }
  return "";
}

struct Family {
  const char* name;
  Kind kind;
  int order, levels, reference;
};

// The time of the solve proper: factorisation, spectrum and iterations.
double solve_seconds(const RunReport& report) {
  return report.timings.get("factorize") + report.timings.get("spectrum") + report.timings.get("solve");
}

}  // namespace

int main(int argc, char** argv) {
  bench::OutArguments arguments;
  if (!bench::parse_out_arguments(argc, argv, "estimate", arguments)) return 2;
  try {
    const std::vector<Family> families =
        arguments.quick
            ? std::vector<Family>{{"hertz-2d", Kind::HalfDisc, 1, 1, 2}}
            : std::vector<Family>{
                  {"hertz-2d", Kind::HalfDisc, 1, 4, 4},          {"hertz-2d", Kind::HalfDisc, 2, 3, 4},
                  {"hertz-3d", Kind::Hemisphere, 1, 2, 2},        {"hertz-3d", Kind::Hemisphere, 2, 1, 2},
                  {"two-cylinders", Kind::TwoCylinders, 1, 3, 4}, {"two-cylinders", Kind::TwoCylinders, 2, 2, 3},
                  {"mindlin-cylinders", Kind::Mindlin, 1, 2, 3}};
    std::ofstream eff(bench::output_path(arguments.out, "effectivity.csv"));
    eff << "scene,order,level,dofs,reference_dofs,strain_energy,reference_energy,true_error,energy_error,estimate,"
           "recovery,contact,effectivity,energy_effectivity,estimate_rate,error_rate,solve_seconds,estimate_seconds\n";
    std::printf(
        "| scene | order | level | DOFs | true error | estimate | recovery | contact | effectivity | rate of η |\n"
        "|---|---|---|---|---|---|---|---|---|---|\n");
    for (const Family& f : families) {
      const RunReport finest = run_scene(parse_scene(level_scene(f.kind, f.reference, f.order), f.name));
      double last_estimate = NAN, last_error = NAN;
      for (int level = 0; level < f.levels; ++level) {
        const RunReport r = run_scene(parse_scene(level_scene(f.kind, level, f.order), f.name));
        const ErrorEstimate& e = *r.error_estimate;
        const double error = energy_distance(*r.model, r.result.u, *finest.model, *finest.qp, finest.result.u);
        // The error from energies, sqrt(2 (E_h − E_ref)) (docs/estimate.md).
        const double difference = e.strain_energy - *finest.strain_energy;
        const double energy_error = difference > 0 ? std::sqrt(2 * difference) : NAN;
        const double rate = std::log2(last_estimate / e.estimate), error_rate = std::log2(last_error / error);
        char line[1024];
        std::snprintf(line, sizeof line,
                      "%s,%d,%d,%lld,%lld,%.12e,%.12e,%.6e,%.6e,%.6e,%.6e,%.6e,%.4f,%.4f,%.3f,%.3f,%.4f,%.4f\n", f.name,
                      f.order, level, r.size.dofs, finest.size.dofs, e.strain_energy, *finest.strain_energy, error,
                      energy_error, e.estimate, e.recovery, e.contact, e.estimate / error, e.estimate / energy_error,
                      rate, error_rate, solve_seconds(r), e.seconds);
        eff << line;
        std::printf("| %s | %d | %d | %lld | %.3g | %.3g | %.3g | %.3g | %.2f | %.2f |\n", f.name, f.order, level,
                    r.size.dofs, error, e.estimate, e.recovery, e.contact, e.estimate / error, rate);
        last_estimate = e.estimate;
        last_error = error;
      }
    }
    const std::vector<std::string> scenes =
        arguments.quick ? std::vector<std::string>{"scenes/hertz.json"}
                        : std::vector<std::string>{"scenes/hertz.json",         "scenes/hertz-order2.json",
                                                   "scenes/hertz-sphere.json",  "scenes/punch.json",
                                                   "scenes/two-cylinders.json", "scenes/mindlin-cylinders.json",
                                                   "scenes/hertz-large.json"};
    std::ofstream cost(bench::output_path(arguments.out, "cost.csv"));
    cost << "scene,dofs,status,solve_seconds,estimate_seconds,ratio,total_seconds,estimate,relative\n";
    std::printf(
        "\n| scene | DOFs | solve [s] | estimate [s] | estimate / solve | relative η |\n|---|---|---|---|---|---|\n");
    for (const std::string& scene : scenes) {
      // The fastest of three runs, so that a busy machine does not decide the ratio.
      RunReport best;
      for (int run = 0; run < (arguments.quick ? 1 : 3); ++run) {
        RunReport r = run_scene(std::string(CONTACTQP_SOURCE_DIR) + "/" + scene);
        if (run == 0 || r.error_estimate->seconds < best.error_estimate->seconds) best = std::move(r);
      }
      const ErrorEstimate& e = *best.error_estimate;
      const double solve = solve_seconds(best);
      char line[512];
      std::snprintf(line, sizeof line, "%s,%lld,%s,%.4f,%.4f,%.4f,%.4f,%.6e,%.6e\n", scene.c_str(), best.size.dofs,
                    to_string(best.result.status).c_str(), solve, e.seconds, e.seconds / solve,
                    best.timings.get("total"), e.estimate, e.relative);
      cost << line;
      std::printf("| %s | %lld | %.3f | %.4f | %.1f%% | %.2f%% |\n", scene.c_str(), best.size.dofs, solve, e.seconds,
                  100 * e.seconds / solve, 100 * e.relative);
    }
    std::ofstream(bench::output_path(arguments.out, "context.json")) << bench::context_json("estimate");
  } catch (const std::exception& error) {
    std::cerr << "bench_estimate: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
