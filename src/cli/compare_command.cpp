// contactqp compare SCENE.json: compare_scene() (run.hpp), then the table, the verdict and the
// JSON. One QP, several backends, the same certificate for each.
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <limits>
#include <set>

#include "commands.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/processes.hpp"
#include "contactqp/run.hpp"
#include "contactqp/solve.hpp"

namespace contactqp::cli {
namespace {

struct CompareArguments {
  SolveArguments solve;
  std::string backends;  // comma-separated; empty: every available backend
};

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

// Empty: compare_scene() takes every available backend that solves the scene's kind of problem.
std::vector<Backend> parse_backend_list(const std::string& text) {
  if (text.empty()) return {};
  std::vector<Backend> backends;
  std::set<Backend> seen;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    const std::string name = text.substr(start, comma - start);
    const Backend backend = parse_backend(name, "--backends");
    if (!seen.insert(backend).second)
      throw InputError("--backends", "= " + text + ": \"" + name + "\" is listed twice");
    backends.push_back(backend);
    start = comma + 1;
  }
  return backends;
}

std::string cell(double x, const char* pattern) { return std::isfinite(x) ? format(pattern, x) : std::string("-"); }

// The contact zone's size column: the half-width b in 2D, the contact radius a in 3D.
std::string table(const std::vector<BackendRun>& runs, int reference, int dim) {
  std::string out =
      format("%-12s %-15s %6s %9s %17s %17s %10s %9s %9s %9s %10s %10s\n", "backend", "status", "iter", "time [s]", "J",
             "theta", "gap (rel)", "KKT max", "du (rel)", "dl (rel)", dim == 2 ? "b" : "a", "p0");
  for (int i = 0; i < static_cast<int>(runs.size()); ++i) {
    const BackendRun& run = runs[i];
    const Certificate& c = run.certificate;
    const double theta = c.dual_available ? c.dual_objective : kNone;
    const double gap = c.dual_available ? c.relative_gap : kNone;
    const std::string name = to_string(run.backend) + (i == reference ? " *" : "");
    out += format("%-12s %-15s %6d %9.3f %17.10e %17s %10s %9.2e %9s %9s %10.6g %10.6g\n", name.c_str(),
                  to_string(run.result.status).c_str(), run.result.iterations, run.result.timings.get("total"),
                  c.objective, cell(theta, "%.10e").c_str(), cell(gap, "%.2e").c_str(), c.kkt_max(),
                  cell(run.rel_diff_u.value_or(kNone), "%.2e").c_str(),
                  cell(run.rel_diff_lambda.value_or(kNone), "%.2e").c_str(),
                  dim == 2 ? run.contact.half_width : run.contact.contact_radius, run.contact.max_pressure);
  }
  return out;
}

int run_compare(const CompareArguments& arguments) {
  // Every check of the input first: a run never computes what it cannot save.
  const SolveArguments& solve_arguments = arguments.solve;
  if (!solve_arguments.json_path.empty()) check_output_path(solve_arguments.json_path, "--json");
  check_distinct_outputs(solve_arguments.scene_path, {{"--json", solve_arguments.json_path}});
  require(solve_arguments.max_elements > 0, "--max-elements", solve_arguments.max_elements, "must be positive");
  CompareOptions options;
  options.backends = parse_backend_list(arguments.backends);
  options.build.max_elements = solve_arguments.max_elements;
  Scene scene = load_scene(solve_arguments.scene_path);
  apply_overrides(solve_arguments, scene.solver);
  const CompareReport report = compare_scene(scene, options);
  // Under mpirun every rank holds every result: rank 0 alone prints and writes the JSON.
  if (process_rank() != 0) return report.agree ? 0 : 1;

  for (const std::string& warning : report.warnings) std::cerr << "contactqp: warning: " << warning << "\n";
  const std::vector<BackendRun>& runs = report.runs;
  // The same solver warnings (an unused PETSc option) would repeat for every backend: once each.
  std::set<std::string> warned;
  for (const BackendRun& run : runs)
    for (const std::string& warning : run.result.warnings)
      if (warned.insert(warning).second) std::cerr << "contactqp: warning: " << warning << "\n";
  std::cout << format("contactqp compare  %s  (%d DOFs, %d contact candidates, tol %g)\n", scene.source.c_str(),
                      report.qp->n_dofs(), report.qp->n_constraints(), report.tol);
  std::cout << table(runs, report.reference, report.model->dim);
  if (report.reference >= 0)
    std::cout << format("* reference: %s (smallest certified gap among converged runs)\n",
                        to_string(runs[report.reference].backend).c_str());
  const Agreement& bound = report.bound;
  std::cout << format("pairwise: du %.2e (<= %.0e), dl %.2e (<= %.0e), max |gap| %.2e (<= %.0e): %s\n",
                      report.max_diff_u, bound.u, report.max_diff_lambda, bound.lambda, report.max_gap, bound.gap,
                      report.agree ? "agree" : (report.all_converged ? "DISAGREE" : "not all converged"));
  if (std::isfinite(report.linear_solve_seconds)) {
    std::string ratios;
    for (const BackendRun& run : runs)
      ratios += format(", %s %.0f", to_string(run.backend).c_str(),
                       run.result.timings.get("total") / report.linear_solve_seconds);
    std::cout << format("one factorisation of K %.3g s, one solve with it %.3g s; time in solves%s\n",
                        report.factorize_seconds, report.linear_solve_seconds, ratios.c_str());
  }
  for (const BackendRun& run : runs) {
    const auto steps = run.result.diagnostics.find("fixed_point_steps");
    if (steps != run.result.diagnostics.end())
      std::cout << format("%s: Coulomb's fixed point in %.0f Tresca solves, last relative change %.2e\n",
                          to_string(run.backend).c_str(), steps->second,
                          run.result.diagnostics.at("fixed_point_change"));
  }
  for (const BackendRun& run : runs)
    if (run.result.status != Status::Converged)
      std::cout << format("%s: %s\n", to_string(run.backend).c_str(), run.result.message.c_str());

  if (!solve_arguments.json_path.empty()) write_file_atomically(solve_arguments.json_path, compare_json(report));
  return report.agree ? 0 : 1;
}

}  // namespace

void add_compare_command(CLI::App& app, int& exit_status) {
  auto arguments = std::make_shared<CompareArguments>();
  SolveArguments& solve = arguments->solve;
  CLI::App* command = app.add_subcommand(
      "compare",
      "Solve one scene with several backends and cross-check them. Exit 0 when all converged, every relative "
      "duality gap is <= 100 T and every pair agrees within 1e4 T in u and 1e5 T in lambda (relative 2-norms, "
      "T = --tol); 1 otherwise; 2 on bad input");
  command->add_option("scene", solve.scene_path, "Scene file (JSON)")->required();
  refuse_empty(
      command->add_option("--backends", arguments->backends,
                          "Comma-separated backends among " + backend_names() + " (default: every available one)"));
  CLI::Option* tol = command->add_option("--tol", solve.tol,
                                         "Relative tolerance T of every backend (default: the scene's solver.tol)");
  refuse_empty(
      command->add_option("--rho", solve.rho, "Uzawa step: auto, a number, or a fraction of rho_max like 0.5x"));
  CLI::Option* max_iterations =
      command->add_option("--max-iterations", solve.max_iterations,
                          "Iteration limit of every backend (default 10000; uzawa on a frictional problem 50000)");
  refuse_empty(command->add_option("--json", solve.json_path, "Write the comparison JSON here"));
  command->add_option("--max-elements", solve.max_elements, "Refuse meshes with more triangles (default 4000000)");
  add_linear_solver_options(*command, solve);
  command->add_option("--backend-option", solve.backend_options,
                      "key=value for every backend, or ipopt.key=value / nlopt.key=value for one (repeatable)");
  command->footer(backends_help());
  command->callback([arguments, tol, max_iterations, &exit_status] {
    arguments->solve.tol_given = tol->count() > 0;
    arguments->solve.max_iterations_given = max_iterations->count() > 0;
    exit_status = run_compare(*arguments);
  });
}

}  // namespace contactqp::cli
