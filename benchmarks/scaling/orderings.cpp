// benchmarks/scaling/orderings: which fill-reducing ordering CHOLMOD should use for K.
// For each Hertz level and each Ordering (auto, amd, metis): analyse and factorise K, one
// solve, and condense() of the contact rows (the active-set backend's extra work), repeated
// --repeats times. For scale, S = B K⁻¹ Bᵀ is also formed the plain way, one dense solve with
// all m columns of Bᵀ (CHOLMOD's blocked multi-right-hand-side solve), when n·m doubles fit in
// 1 GiB. Writes orderings.csv and orderings-context.json (docs/scaling.md, "Orderings").
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <sstream>

#include "contactqp/cholesky.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/io.hpp"
#include "contactqp/model.hpp"
#include "context.hpp"
#include "hertz_levels.hpp"

using namespace contactqp;
using namespace contactqp::bench;

namespace {

struct Arguments {
  std::string out = std::string(CONTACTQP_SOURCE_DIR) + "/benchmarks/scaling/results";
  std::string levels = "5,6,7,8";
  int repeats = 2;
};

int run(const Arguments& arguments) {
  require(arguments.repeats > 0, "--repeats", arguments.repeats, "must be positive");
  const std::vector<int> levels = parse_levels(arguments.levels, "--levels");
  make_directory(arguments.out);
  write_file_atomically(arguments.out + "/orderings-context.json",
                        context_json("orderings", "{\"benchmark\": \"orderings\", \"levels\": \"" + arguments.levels +
                                                      "\", \"repeats\": " + std::to_string(arguments.repeats) + "}"));
  const std::string csv_path = arguments.out + "/orderings.csv";
  std::string csv =
      "level,dofs,constraints,ordering,repeat,analyse_seconds,factorize_seconds,solve_seconds,condense_seconds,"
      "factor_nonzeros,reached_columns,dense_solve_seconds\n";
  const std::pair<Ordering, const char*> orderings[] = {
      {Ordering::Auto, "auto"}, {Ordering::Amd, "amd"}, {Ordering::Metis, "metis"}};
  for (int k : levels) {
    QuadraticProgram qp;
    {
      Model model = build_model(parse_scene(hertz_scene_text(hertz_levels()[k]), "hertz level " + std::to_string(k)));
      qp = assemble_qp(model);
    }
    for (int repeat = 0; repeat < arguments.repeats; ++repeat) {
      for (const auto& [ordering, name] : orderings) {
        const CholeskyFactor factor(qp.K, ordering);
        if (!factor.ok()) throw std::runtime_error("K is not positive definite: " + factor.message());
        Stopwatch clock;
        const VectorXd u = factor.solve(qp.f);
        const double solve_seconds = clock.seconds();
        clock.restart();
        const Condensation condensed = factor.condense(qp.B, qp.f);
        const double condense_seconds = clock.seconds();
        double dense_solve_seconds = NAN;
        if (8.0 * qp.n_dofs() * qp.n_constraints() <= 1024.0 * 1024.0 * 1024.0) {
          const Eigen::MatrixXd Bt(qp.B.transpose());
          clock.restart();
          const Eigen::MatrixXd S = qp.B * factor.solve_columns(Bt);
          dense_solve_seconds = clock.seconds();
        }
        std::ostringstream line;
        line.precision(6);
        line << k << ',' << qp.n_dofs() << ',' << qp.n_constraints() << ',' << name << '(' << factor.ordering_name()
             << ")," << repeat << ',' << factor.analyse_seconds() << ',' << factor.factorize_seconds() << ','
             << solve_seconds << ',' << condense_seconds << ',' << factor.factor_nonzeros() << ','
             << condensed.reached_columns << ',';
        if (std::isfinite(dense_solve_seconds)) line << dense_solve_seconds;
        line << '\n';
        csv += line.str();
        std::cout << line.str();
      }
    }
    write_file_atomically(csv_path, csv);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Ordering study: analyse, factorise, solve and condense K with AMD, METIS and CHOLMOD's default"};
  Arguments arguments;
  app.add_option("--out", arguments.out, "Directory for orderings.csv");
  app.add_option("--levels", arguments.levels, "Mesh levels (benchmarks/scaling), default 5,6,7,8");
  app.add_option("--repeats", arguments.repeats, "Measurements per ordering and level");
  CLI11_PARSE(app, argc, argv);
  try {
    return run(arguments);
  } catch (const InputError& error) {
    std::cerr << "ordering_benchmark: error: " << error.what() << "\n";
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "ordering_benchmark: error: " << error.what() << "\n";
    return 1;
  }
}
