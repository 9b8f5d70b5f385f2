// Accuracy against DOFs for 3-node and 6-node triangles on Hertz's problem (scenes/hertz.json):
// one row per mesh, written to element_order.csv, with context.json beside it. plot.py draws
// the errors against the DOFs and prints the DOFs each order needs for a given accuracy.
//
//   ./build/bench_element_order [--out DIR] [--quick]
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "contactqp/errors.hpp"
#include "contactqp/io.hpp"
#include "contactqp/post.hpp"
#include "contactqp/run.hpp"
#include "contactqp/solve.hpp"
#include "out_arguments.hpp"

using namespace contactqp;

namespace {

// docs/architecture.md: an independent finite-element code gives P ≈ 0.008657 E R on this geometry.
constexpr double kReferenceForce = 0.008657;

// A family of meshes: one element order and grading, refined by contact_size.
struct Family {
  std::string name;
  int order;
  double size, grading;
  std::vector<double> contact_sizes;
};

std::vector<Family> families(bool quick) {
  if (quick) return {{"order1", 1, 0.1, 0.1, {0.004}}, {"order2_graded", 2, 0.25, 0.3, {0.016}}};
  return {
      // The shipped scene's family: linear triangles need slow grading (see order1_fast).
      {"order1", 1, 0.1, 0.1, {0.008, 0.0057, 0.004, 0.0028, 0.002, 0.0014, 0.001, 0.0007, 0.0005}},
      {"order1_fast", 1, 0.25, 0.3, {0.004, 0.002, 0.001, 0.0005}},
      // Quadratic triangles on the same meshes, and graded three times faster.
      {"order2", 2, 0.1, 0.1, {0.032, 0.016, 0.008, 0.004, 0.002}},
      {"order2_graded", 2, 0.25, 0.3, {0.032, 0.024, 0.016, 0.012, 0.008, 0.006, 0.004, 0.003, 0.002}},
  };
}

std::string read_text(const std::string& path) {
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

std::string command_output(const std::string& command) {
  std::string out;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[256];
    while (fgets(buffer, sizeof buffer, pipe)) out += buffer;
    pclose(pipe);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
  return out;
}

std::string context_json() {
  char date[64];
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  nlohmann::json context = {
      {"benchmark", "element_order"},
      {"git_revision", command_output("git -C " CONTACTQP_SOURCE_DIR " rev-parse HEAD 2>/dev/null")},
      {"git_dirty", !command_output("git -C " CONTACTQP_SOURCE_DIR " status --porcelain 2>/dev/null").empty()},
      {"compiler", std::string("g++ ") + __VERSION__},
      {"build_type", CONTACTQP_BUILD_TYPE},
      {"cores", std::thread::hardware_concurrency()},
      {"date", date},
      {"scene", "scenes/hertz.json"}};
  return context.dump(2) + "\n";
}

}  // namespace

int main(int argc, char** argv) {
  bench::OutArguments arguments;
  if (!bench::parse_out_arguments(argc, argv, "element_order", arguments)) return 2;
  const bool quick = arguments.quick;
  const std::string out_directory = arguments.out;
  const std::string csv_path = bench::output_path(out_directory, "element_order.csv");

  std::ostringstream csv;
  csv.precision(10);
  csv << "family,order,size,grading,contact_size,nodes,elements,dofs,constraints,status,iterations,force,"
         "force_error,error_half_width,error_max_pressure,error_l2,seconds\n";
  const std::string scene_text = read_text(CONTACTQP_SOURCE_DIR "/scenes/hertz.json");
  for (const Family& family : families(quick)) {
    for (double contact_size : family.contact_sizes) {
      Stopwatch clock;
      Scene scene = parse_scene(scene_text, CONTACTQP_SOURCE_DIR "/scenes/hertz.json");
      scene.body.mesh.order = family.order;
      scene.body.mesh.size = family.size;
      scene.body.mesh.grading = family.grading;
      scene.body.mesh.contact_size = contact_size;
      scene.solver.max_iterations = 200000;
      const RunReport report = run_scene(scene);
      const Model& model = *report.model;
      const QuadraticProgram& qp = *report.qp;
      const SolveResult& result = report.result;
      const ContactSummary& contact = report.contact;
      const auto& hertz = report.hertz;
      const double seconds = clock.seconds();
      csv << family.name << ',' << family.order << ',' << family.size << ',' << family.grading << ',' << contact_size
          << ',' << model.mesh.n_nodes() << ',' << model.mesh.n_elements() << ',' << qp.n_dofs() << ','
          << qp.n_constraints() << ',' << to_string(result.status) << ',' << result.iterations << ','
          << contact.total_force << ',' << contact.total_force / kReferenceForce - 1 << ','
          << (hertz ? hertz->error_half_width : NAN) << ',' << (hertz ? hertz->error_max_pressure : NAN) << ','
          << (hertz ? hertz->error_l2 : NAN) << ',' << seconds << '\n';
      std::cout << family.name << " contact_size " << contact_size << ": " << qp.n_dofs() << " DOFs, L2 error "
                << (hertz ? 100 * hertz->error_l2 : NAN) << "%, " << seconds << " s" << std::endl;
    }
  }
  write_file_atomically(csv_path, csv.str());
  write_file_atomically(out_directory + "/context.json", context_json());
  std::cout << "wrote " << csv_path << " and context.json\n";
  return 0;
}
