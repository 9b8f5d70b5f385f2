// Hertz accuracy as ν → 0.5 in plane strain, for 3-node triangles, 6-node triangles and the
// mixed formulation (body.formulation "mixed"): one row per (variant, ν), written to
// incompressible.csv with context.json beside it. plot.py draws the errors against 0.5 − ν
// and prints the README's table.
//
//   ./build/benchmarks/incompressible/bench_incompressible [--out DIR] [--quick]
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "contactqp/io.hpp"
#include "contactqp/post.hpp"
#include "contactqp/run.hpp"
#include "contactqp/solve.hpp"
#include "context.hpp"
#include "out_arguments.hpp"

using namespace contactqp;

namespace {

// A discretisation: a shipped scene, its formulation, and optionally another contact size.
struct Variant {
  std::string name, scene, formulation;
  double contact_size = 0;  // 0: the scene's
};

std::vector<Variant> variants(bool quick) {
  if (quick)
    return {{"order2", "scenes/hertz-order2.json", "displacement"}, {"mixed", "scenes/hertz-order2.json", "mixed"}};
  return {
      {"order1", "scenes/hertz.json", "displacement"},                     // 3 730 DOFs, the shipped Hertz scene
      {"order2", "scenes/hertz-order2.json", "displacement"},              // 894 DOFs
      {"mixed", "scenes/hertz-order2.json", "mixed"},                      // the same mesh, mixed
      {"order2_fine", "scenes/hertz-order2.json", "displacement", 0.004},  // 2 710 DOFs
      {"mixed_fine", "scenes/hertz-order2.json", "mixed", 0.004},
  };
}

std::vector<double> poisson_ratios(bool quick) {
  if (quick) return {0.499};
  return {0.3, 0.45, 0.49, 0.499, 0.4999};
}

}  // namespace

int main(int argc, char** argv) {
  bench::OutArguments arguments;
  if (!bench::parse_out_arguments(argc, argv, "incompressible", arguments)) return 2;
  const bool quick = arguments.quick;
  const std::string out_directory = arguments.out;
  const std::string csv_path = bench::output_path(out_directory, "incompressible.csv");

  std::ostringstream csv;
  csv.precision(10);
  csv << "variant,order,formulation,contact_size,nu,dofs,constraints,status,iterations,force,error_half_width,"
         "error_max_pressure,error_l2,seconds\n";
  for (const Variant& variant : variants(quick)) {
    const std::string path = CONTACTQP_SOURCE_DIR "/" + variant.scene;
    for (double nu : poisson_ratios(quick)) {
      Stopwatch clock;
      Scene scene = load_scene(path);
      scene.material.nu = nu;
      scene.body.formulation = variant.formulation == "mixed" ? Formulation::Mixed : Formulation::Displacement;
      if (variant.contact_size > 0) scene.body.mesh.contact_size = variant.contact_size;
      // The answer does not depend on the backend (tests/cross_backend); L-BFGS is the fastest.
      scene.solver.backend = Backend::Nlopt;
      scene.solver.max_iterations = 100000;
      const RunReport report = run_scene(scene);
      const Model& model = *report.model;
      const QuadraticProgram& qp = *report.qp;
      const SolveResult& result = report.result;
      const ContactSummary& contact = report.contact;
      const auto& hertz = report.hertz;
      const double seconds = clock.seconds();
      csv << variant.name << ',' << model.mesh.order << ',' << variant.formulation << ','
          << scene.body.mesh.contact_size << ',' << nu << ',' << qp.n_dofs() << ',' << qp.n_constraints() << ','
          << to_string(result.status) << ',' << result.iterations << ',' << contact.total_force << ','
          << (hertz ? hertz->error_half_width : NAN) << ',' << (hertz ? hertz->error_max_pressure : NAN) << ','
          << (hertz ? hertz->error_l2 : NAN) << ',' << seconds << '\n';
      std::cout << variant.name << " nu " << nu << ": " << qp.n_dofs() << " DOFs, b "
                << (hertz ? 100 * hertz->error_half_width : NAN) << "%, p0 "
                << (hertz ? 100 * hertz->error_max_pressure : NAN) << "%, L2 " << (hertz ? 100 * hertz->error_l2 : NAN)
                << "%, " << to_string(result.status) << std::endl;
    }
  }
  write_file_atomically(csv_path, csv.str());
  write_file_atomically(
      out_directory + "/context.json",
      bench::context_json("incompressible",
                          R"({"backend": "nlopt", "scenes": ["scenes/hertz.json", "scenes/hertz-order2.json"]})"));
  std::cout << "wrote " << csv_path << " and context.json\n";
  return 0;
}
