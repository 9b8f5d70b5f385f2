// The cost of a frictional step (issue 24): active_set on a load path with Coulomb friction,
// each step's time against the unit of cost, one factorisation of K and one solve with it
// (docs/architecture.md), measured in the same run. Scenes: plane-2d.json (a half disc on a
// plane, ~1e5 DOFs) and sphere-3d.json (a hemisphere on a plane, ~5e4 DOFs or more), each pushed
// and then sheared. Per step: the warm-started step of the path (the last step's answer and
// factor of K, as solve_load_steps does) and the same step solved from scratch (its own
// factorisation, no initial guess). Writes steps.csv and context.json; prints the figures of
// docs/friction-backends.md.
//
//   ./build/benchmarks/friction/bench_friction [--out DIR] [--quick]
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "contact/contact.hpp"
#include "contactqp/cholesky.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/io.hpp"
#include "contactqp/run.hpp"
#include "contactqp/solve.hpp"
#include "context.hpp"
#include "out_arguments.hpp"
#include "qp/norms.hpp"

using namespace contactqp;

namespace {

struct Case {
  std::string name, file;
  double quick_size, quick_contact_size;  // --quick: a coarse mesh, seconds in all
};

// The unit of cost: one factorisation of K and the fastest of three solves with it.
double unit_of_cost(const QuadraticProgram& qp, double* factorize_seconds, double* solve_seconds) {
  Stopwatch clock;
  const CholeskyFactor factor(qp.K);
  *factorize_seconds = clock.seconds();
  if (!factor.ok()) throw InputError("K", "cannot be factorised: " + factor.message());
  *solve_seconds = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    clock.restart();
    factor.solve(qp.f);
    *solve_seconds = std::min(*solve_seconds, clock.seconds());
  }
  return *factorize_seconds + *solve_seconds;
}

double diagnostic(const SolveResult& result, const char* key) {
  const auto found = result.diagnostics.find(key);
  return found == result.diagnostics.end() ? 0.0 : found->second;
}

void run_case(const Case& c, bool quick, std::ostringstream& csv) {
  Scene scene = load_scene(CONTACTQP_SOURCE_DIR "/benchmarks/friction/" + c.file);
  if (quick) {
    scene.body.mesh.size = c.quick_size;
    scene.body.mesh.contact_size = c.quick_contact_size;
  }
  Model model = build_model(scene);
  QuadraticProgram qp = assemble_qp(model);
  double factorize = 0, linear_solve = 0;
  const double unit = unit_of_cost(qp, &factorize, &linear_solve);
  std::cout << c.name << ": " << qp.n_dofs() << " DOFs, " << qp.n_constraints() << " contact rows, "
            << qp.friction.T.rows() << " tangential rows; unit of cost " << std::setprecision(3) << unit
            << " s (factorise " << factorize << " s + solve " << linear_solve << " s)\n";

  // The path as solve_load_steps runs it, one step at a time so that each can also be solved
  // from scratch on the same QP.
  const std::vector<std::vector<double>> factors = load_factors(scene);
  Eigen::VectorXd positions = Eigen::VectorXd::Zero(qp.friction.T.rows());
  SolveOptions options = scene.solver;
  SolveResult last;
  for (size_t k = 0; k < factors.size(); ++k) {
    apply_load_step(model, qp, factors[k], scene.steps[k].path);
    detail::set_friction_offset(model, qp, positions);
    const SolveOptions cold_options = scene.solver;  // from scratch: no guess, its own factor
    Stopwatch clock;
    const SolveResult cold = solve(qp, cold_options);
    const double cold_seconds = clock.seconds();
    SolveResult warm = cold;
    double warm_seconds = cold_seconds;
    if (k > 0) {  // step 1 has nothing to start from: it is its own warm step
      clock.restart();
      warm = solve(qp, options);
      warm_seconds = clock.seconds();
    }
    positions = detail::tangential_positions(model, warm.u);
    options.K_factor = warm.K_factor ? warm.K_factor : cold.K_factor;
    options.initial = {warm.u, warm.lambda, warm.lambda_t};
    const double difference = relative_difference(warm.u, cold.u);
    std::cout << "  step " << k + 1 << ": from scratch " << cold_seconds << " s = " << cold_seconds / unit << " units ("
              << to_string(cold.status) << ", " << cold.iterations << " Newton/gradient steps, "
              << diagnostic(cold, "fixed_point_steps") << " Tresca solves); warm-started " << warm_seconds
              << " s = " << warm_seconds / unit << " units (" << to_string(warm.status) << ", " << warm.iterations
              << " steps, " << diagnostic(warm, "fixed_point_steps") << " Tresca solves); stick/slip/gap nodes "
              << diagnostic(warm, "stick_nodes") << "/" << diagnostic(warm, "slip_nodes") << "/"
              << diagnostic(warm, "gap_nodes") << "; |u_warm - u_cold|/|u| " << difference << "\n";
    csv << c.name << ',' << qp.n_dofs() << ',' << qp.n_constraints() << ',' << k + 1 << ',' << factorize << ','
        << linear_solve << ',' << cold_seconds << ',' << to_string(cold.status) << ',' << cold.iterations << ','
        << diagnostic(cold, "fixed_point_steps") << ',' << warm_seconds << ',' << to_string(warm.status) << ','
        << warm.iterations << ',' << diagnostic(warm, "fixed_point_steps") << ',' << diagnostic(warm, "stick_nodes")
        << ',' << diagnostic(warm, "slip_nodes") << ',' << diagnostic(warm, "gap_nodes") << ',' << difference << '\n';
  }
}

}  // namespace

int main(int argc, char** argv) {
  bench::OutArguments arguments;
  if (!bench::parse_out_arguments(argc, argv, "friction", arguments)) return 2;
  try {
    std::ostringstream csv;
    csv.precision(10);
    csv << "scene,dofs,contact_rows,step,factorize_seconds,solve_seconds,cold_seconds,cold_status,cold_iterations,"
           "cold_fixed_point_steps,warm_seconds,warm_status,warm_iterations,warm_fixed_point_steps,stick_nodes,"
           "slip_nodes,gap_nodes,relative_difference_u\n";
    const std::vector<Case> cases = {{"plane-2d", "plane-2d.json", 0.2, 0.01},
                                     {"sphere-3d", "sphere-3d.json", 0.4, 0.06}};
    for (const Case& c : cases) run_case(c, arguments.quick, csv);
    write_file_atomically(bench::output_path(arguments.out, "steps.csv"), csv.str());
    write_file_atomically(arguments.out + "/context.json",
                          bench::context_json("friction", arguments.quick ? R"({"quick": true})" : "{}"));
    std::cout << "wrote steps.csv and context.json in " << arguments.out << "\n";
  } catch (const InputError& error) {
    std::cerr << "bench_friction: " << error.what() << "\n";
    return 2;
  }
  return 0;
}
