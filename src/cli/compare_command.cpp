// contactqp compare SCENE.json: one QP, several backends, the same certificate for each, and
// how far their answers lie from each other. A dual method and a primal one that agree to
// the tolerance validate each other.
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>

#include "commands.hpp"
#include "contactqp/certificate.hpp"
#include "contactqp/cholesky.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/solve.hpp"

namespace contactqp::cli {
namespace {

using nlohmann::json;

// How closely converged backends must agree at tolerance T for `compare` to exit 0 (README,
// "Choosing a backend"). Each backend stops when its relative KKT residuals are below T; the
// error of a solution is that residual amplified by the conditioning of the contact problem,
// more so for λ (a force read off B K⁻¹ Bᵀ) than for u. The factors leave room for that on
// the shipped scenes and still catch a wrong answer, which differs at the percent level.
struct Agreement {
  double u, lambda, gap;  // bounds on ‖u_a − u_b‖/‖u_b‖, ‖λ_a − λ_b‖/‖λ_b‖, |relative gap|
};
Agreement agreement_for(double tol) { return {1e4 * tol, 1e5 * tol, 1e2 * tol}; }

struct CompareArguments {
  SolveArguments solve;
  std::string backends;  // comma-separated; empty: every available backend
};

struct Run {
  Backend backend;
  SolveResult result;
  Certificate certificate;
  ContactSummary contact;
  std::optional<double> rel_diff_u, rel_diff_lambda;  // against the reference run
};

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

std::vector<Backend> parse_backend_list(const std::string& text) {
  if (text.empty()) return available_backends();
  std::vector<Backend> backends;
  std::set<Backend> seen;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    const std::string name = text.substr(start, comma - start);
    const Backend backend = parse_backend(name, "--backends");
    if (!seen.insert(backend).second) throw InputError("--backends", "= " + text + ": \"" + name + "\" is listed twice");
    backends.push_back(backend);
    start = comma + 1;
  }
  return backends;
}

// ‖a − b‖ / ‖b‖, or the absolute difference when b = 0.
double relative_difference(const VectorXd& a, const VectorXd& b) {
  const double scale = b.norm();
  return scale > 0 ? (a - b).norm() / scale : (a - b).norm();
}

// Symmetric, for the pairwise check: ‖a − b‖ / max(‖a‖, ‖b‖).
double symmetric_difference(const VectorXd& a, const VectorXd& b) {
  const double scale = std::max(a.norm(), b.norm());
  return scale > 0 ? (a - b).norm() / scale : 0.0;
}

bool converged(const Run& run) { return run.result.status == Status::Converged; }

// The converged run with the smallest certified |relative gap|; the run with a certificate
// otherwise. -1 when no run has a dual objective to compare.
int choose_reference(const std::vector<Run>& runs) {
  int best = -1;
  auto better = [&](int i) {
    if (!runs[i].certificate.dual_available) return false;
    if (best < 0) return true;
    if (converged(runs[i]) != converged(runs[best])) return converged(runs[i]);
    return std::abs(runs[i].certificate.relative_gap) < std::abs(runs[best].certificate.relative_gap);
  };
  for (int i = 0; i < static_cast<int>(runs.size()); ++i)
    if (better(i)) best = i;
  return best;
}

std::string cell(double x, const char* pattern) {
  return std::isfinite(x) ? format(pattern, x) : std::string("-");
}

std::string table(const std::vector<Run>& runs, int reference) {
  std::string out = format("%-12s %-15s %6s %9s %17s %17s %10s %9s %9s %9s %10s %10s\n", "backend", "status", "iter",
                           "time [s]", "J", "theta", "gap (rel)", "KKT max", "du (rel)", "dl (rel)", "b", "p0");
  for (int i = 0; i < static_cast<int>(runs.size()); ++i) {
    const Run& run = runs[i];
    const Certificate& c = run.certificate;
    const double theta = c.dual_available ? c.dual_objective : kNone;
    const double gap = c.dual_available ? c.relative_gap : kNone;
    const std::string name = to_string(run.backend) + (i == reference ? " *" : "");
    out += format("%-12s %-15s %6d %9.3f %17.10e %17s %10s %9.2e %9s %9s %10.6g %10.6g\n", name.c_str(),
                  to_string(run.result.status).c_str(), run.result.iterations, run.result.timings.get("total"),
                  c.objective, cell(theta, "%.10e").c_str(), cell(gap, "%.2e").c_str(), c.kkt_max(),
                  cell(run.rel_diff_u.value_or(kNone), "%.2e").c_str(),
                  cell(run.rel_diff_lambda.value_or(kNone), "%.2e").c_str(), run.contact.half_width,
                  run.contact.max_pressure);
  }
  return out;
}

json number(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }
json number(const std::optional<double>& x) { return x ? number(*x) : json(nullptr); }

int run_compare(const CompareArguments& arguments) {
  Stopwatch total;
  // Every check of the input first: a run never computes what it cannot save.
  const SolveArguments& solve_arguments = arguments.solve;
  if (!solve_arguments.json_path.empty()) check_output_path(solve_arguments.json_path, "--json");
  check_distinct_outputs(solve_arguments.scene_path, {{"--json", solve_arguments.json_path}});
  require(solve_arguments.max_elements > 0, "--max-elements", solve_arguments.max_elements, "must be positive");
  const std::vector<Backend> backends = parse_backend_list(arguments.backends);
  Scene scene = load_scene(solve_arguments.scene_path);
  apply_overrides(solve_arguments, scene.solver);
  std::vector<SolveOptions> options;
  for (Backend backend : backends) {
    options.push_back(scene.solver);
    options.back().backend = backend;
    validate_options(options.back());
  }

  BuildOptions build;
  build.max_elements = solve_arguments.max_elements;
  Model model = build_model(scene, build);
  QuadraticProgram qp = assemble_qp(model);
  for (const std::string& warning : model.warnings) std::cerr << "contactqp: warning: " << warning << "\n";

  // The unit of cost (ARCHITECTURE.md): one factorisation of K and one solve with it. The
  // same factor certifies every run, so that all are judged by the same numbers.
  Stopwatch clock;
  const CholeskyFactor K_factor(qp.K);
  const double factorize_seconds = clock.seconds();
  double linear_solve_seconds = K_factor.ok() ? std::numeric_limits<double>::infinity() : kNone;
  for (int k = 0; k < 5 && K_factor.ok(); ++k) {  // the fastest of a few: the first one warms caches
    clock.restart();
    K_factor.solve(qp.f);
    linear_solve_seconds = std::min(linear_solve_seconds, clock.seconds());
  }

  // Each backend from scratch (its own factorisation included), so that the times compare.
  std::vector<Run> runs;
  for (const SolveOptions& run_options : options) {
    Run run{run_options.backend, solve(qp, run_options), {}, {}, {}, {}};
    run.result.K_factor.reset();  // a factor per backend is memory the next one may need
    run.certificate = certify(qp, run.result.u, run.result.lambda, &K_factor);
    run.contact = summarize_contact(model, qp, run.result.u, run.result.lambda);
    runs.push_back(std::move(run));
  }

  // The same solver warnings (an unused PETSc option) would repeat for every backend: once each.
  std::set<std::string> warned;
  for (const Run& run : runs)
    for (const std::string& warning : run.result.warnings)
      if (warned.insert(warning).second) std::cerr << "contactqp: warning: " << warning << "\n";

  const int reference = choose_reference(runs);
  if (reference >= 0)
    for (Run& run : runs) {
      run.rel_diff_u = relative_difference(run.result.u, runs[reference].result.u);
      run.rel_diff_lambda = relative_difference(run.result.lambda, runs[reference].result.lambda);
    }

  // Exit 0 only when every run converged, every certified gap is small and every pair agrees.
  const Agreement bound = agreement_for(scene.solver.tol);
  double max_diff_u = 0, max_diff_lambda = 0, max_gap = 0;
  bool all_converged = true;
  for (size_t i = 0; i < runs.size(); ++i) {
    all_converged = all_converged && converged(runs[i]) && runs[i].certificate.dual_available;
    max_gap = std::max(max_gap, std::abs(runs[i].certificate.relative_gap));
    for (size_t j = 0; j < i; ++j) {
      max_diff_u = std::max(max_diff_u, symmetric_difference(runs[i].result.u, runs[j].result.u));
      max_diff_lambda = std::max(max_diff_lambda, symmetric_difference(runs[i].result.lambda, runs[j].result.lambda));
    }
  }
  const bool agree = all_converged && max_diff_u <= bound.u && max_diff_lambda <= bound.lambda && max_gap <= bound.gap;

  std::cout << format("contactqp compare  %s  (%d DOFs, %d contact candidates, tol %g)\n", scene.source.c_str(),
                      qp.n_dofs(), qp.n_constraints(), scene.solver.tol);
  std::cout << table(runs, reference);
  if (reference >= 0)
    std::cout << format("* reference: %s (smallest certified gap among converged runs)\n",
                        to_string(runs[reference].backend).c_str());
  std::cout << format("pairwise: du %.2e (<= %.0e), dl %.2e (<= %.0e), max |gap| %.2e (<= %.0e): %s\n", max_diff_u,
                      bound.u, max_diff_lambda, bound.lambda, max_gap, bound.gap,
                      agree ? "agree" : (all_converged ? "DISAGREE" : "not all converged"));
  if (K_factor.ok()) {
    std::string ratios;
    for (const Run& run : runs)
      ratios += format(", %s %.0f", to_string(run.backend).c_str(), run.result.timings.get("total") / linear_solve_seconds);
    std::cout << format("one factorisation of K %.3g s, one solve with it %.3g s; time in solves%s\n",
                        factorize_seconds, linear_solve_seconds, ratios.c_str());
  }
  for (const Run& run : runs)
    if (!converged(run))
      std::cout << format("%s: %s\n", to_string(run.backend).c_str(), run.result.message.c_str());

  if (!solve_arguments.json_path.empty()) {
    json out;
    out["scene"] = scene.source;
    out["tol"] = number(scene.solver.tol);
    out["dofs"] = qp.n_dofs();
    out["constraints"] = qp.n_constraints();
    out["reference"] = reference >= 0 ? json(to_string(runs[reference].backend)) : json(nullptr);
    out["agreement"] = {{"rel_diff_u", number(bound.u)},
                        {"rel_diff_lambda", number(bound.lambda)},
                        {"relative_duality_gap", number(bound.gap)}};
    out["max_pairwise_rel_diff_u"] = number(max_diff_u);
    out["max_pairwise_rel_diff_lambda"] = number(max_diff_lambda);
    out["agree"] = agree;
    out["factorize_seconds"] = number(factorize_seconds);
    out["linear_solve_seconds"] = number(linear_solve_seconds);
    json list = json::array();
    for (const Run& run : runs) {
      const Certificate& c = run.certificate;
      json timings = json::object();
      for (const auto& [phase, seconds] : run.result.timings.phases()) timings[phase] = number(seconds);
      list.push_back({{"backend", to_string(run.backend)},
                      {"status", to_string(run.result.status)},
                      {"message", run.result.message},
                      {"iterations", run.result.iterations},
                      {"seconds", number(run.result.timings.get("total"))},
                      {"seconds_in_linear_solves", number(run.result.timings.get("total") / linear_solve_seconds)},
                      {"objective", number(c.objective)},
                      {"dual_objective", c.dual_available ? number(c.dual_objective) : json(nullptr)},
                      {"duality_gap", c.dual_available ? number(c.duality_gap) : json(nullptr)},
                      {"relative_duality_gap", c.dual_available ? number(c.relative_gap) : json(nullptr)},
                      {"kkt_max", number(c.kkt_max())},
                      {"rel_diff_u", number(run.rel_diff_u)},
                      {"rel_diff_lambda", number(run.rel_diff_lambda)},
                      {"half_width", number(run.contact.half_width)},
                      {"max_pressure", number(run.contact.max_pressure)},
                      {"total_force", number(run.contact.total_force)},
                      {"timings", timings}});
    }
    out["runs"] = list;
    out["timings"] = {{"mesh", number(model.timings.get("mesh"))},
                      {"assemble", number(model.timings.get("assemble"))},
                      {"total", number(total.seconds())}};
    write_file_atomically(solve_arguments.json_path, out.dump(2) + "\n");
  }
  return agree ? 0 : 1;
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
  command->add_option("--backends", arguments->backends,
                      "Comma-separated backends, e.g. uzawa,ipopt,nlopt (default: every available one)");
  CLI::Option* tol = command->add_option("--tol", solve.tol, "Relative tolerance T of every backend (default: the scene's solver.tol)");
  command->add_option("--rho", solve.rho, "Uzawa step: auto, a number, or a fraction of rho_max like 0.5x");
  CLI::Option* max_iterations =
      command->add_option("--max-iterations", solve.max_iterations, "Iteration limit of every backend (default 10000)");
  command->add_option("--json", solve.json_path, "Write the comparison JSON here");
  command->add_option("--max-elements", solve.max_elements, "Refuse meshes with more triangles (default 4000000)");
  add_linear_solver_options(*command, solve);
  command->add_option("--backend-option", solve.backend_options,
                      "key=value for every backend, or ipopt.key=value / nlopt.key=value for one (repeatable)");
  command->callback([arguments, tol, max_iterations, &exit_status] {
    arguments->solve.tol_given = tol->count() > 0;
    arguments->solve.max_iterations_given = max_iterations->count() > 0;
    exit_status = run_compare(*arguments);
  });
}

}  // namespace contactqp::cli
