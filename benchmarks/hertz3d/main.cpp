// 3D accuracy against DOFs: Hertz's sphere (scenes/hertz-sphere.json) meshed with 4-node and
// 10-node tetrahedra, refined by contact_size; and Boussinesq's punch (scenes/punch.json) on
// blocks growing from 10a to 40a and meshes refined at the rim. Writes sphere.csv and punch.csv
// (one row per run) and context.json; plot.py draws the errors against the DOFs, fits the
// observed order, and prints the tables of docs/3d.md.
//
//   ./build/benchmarks/hertz3d/bench_hertz3d [--out DIR] [--quick]
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "contactqp/errors.hpp"
#include "contactqp/io.hpp"
#include "contactqp/post.hpp"
#include "contactqp/solve.hpp"
#include "context.hpp"
#include "out_arguments.hpp"

using namespace contactqp;

namespace {

std::string read_text(const std::string& path) {
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

struct Run {
  Model model;
  QuadraticProgram qp;
  SolveResult result;
  ContactSummary contact;
  double seconds = 0;
};

Run run(Scene scene) {
  Stopwatch clock;
  Run out;
  out.model = build_model(scene);
  out.qp = assemble_qp(out.model);
  out.result = solve(out.qp, scene.solver);
  out.contact = summarize_contact(out.model, out.qp, out.result.u, out.result.lambda);
  out.seconds = clock.seconds();
  return out;
}

// One family of sphere meshes: an element order refined by contact_size (units of R).
struct Family {
  int order;
  std::vector<double> contact_sizes;
};

void sphere_study(bool quick, std::ostringstream& csv) {
  csv << "order,contact_size,nodes,elements,dofs,constraints,status,iterations,force,contact_radius,max_pressure,"
         "error_contact_radius,error_max_pressure,error_l2,seconds\n";
  const std::vector<Family> families = quick ? std::vector<Family>{{1, {0.04}}, {2, {0.06}}}
                                             : std::vector<Family>{{1, {0.04, 0.028, 0.02, 0.014, 0.01, 0.007, 0.005}},
                                                                   {2, {0.06, 0.04, 0.028, 0.02, 0.014, 0.01}}};
  const std::string path = CONTACTQP_SOURCE_DIR "/scenes/hertz-sphere.json";
  const std::string text = read_text(path);
  for (const Family& family : families) {
    for (double cs : family.contact_sizes) {
      Scene scene = parse_scene(text, path);
      scene.body.mesh.order = family.order;
      scene.body.mesh.contact_size = cs;
      const Run r = run(scene);
      const auto hertz = compare_with_hertz(r.model, r.contact);
      csv << family.order << ',' << cs << ',' << r.model.mesh.n_nodes() << ',' << r.model.mesh.n_elements() << ','
          << r.qp.n_dofs() << ',' << r.qp.n_constraints() << ',' << to_string(r.result.status) << ','
          << r.result.iterations << ',' << r.contact.total_force << ',' << r.contact.contact_radius << ','
          << r.contact.max_pressure << ',' << (hertz ? hertz->error_contact_radius : NAN) << ','
          << (hertz ? hertz->error_max_pressure : NAN) << ',' << (hertz ? hertz->error_l2 : NAN) << ',' << r.seconds
          << '\n';
      std::cout << "sphere order " << family.order << " contact_size " << cs << ": " << r.qp.n_dofs() << " DOFs, L2 "
                << (hertz ? 100 * hertz->error_l2 : NAN) << "%, " << r.seconds << " s" << std::endl;
    }
  }
}

void punch_study(bool quick, std::ostringstream& csv) {
  csv << "block,contact_size,size,nodes,elements,dofs,constraints,status,iterations,force,boussinesq_force,"
         "error_force,shape_error,seconds\n";
  // Blocks of side L (units of the punch radius a = 1), each with the mesh refined at the rim.
  struct Case {
    double block, contact_size;
  };
  const std::vector<Case> cases = quick ? std::vector<Case>{{10, 0.15}}
                                        : std::vector<Case>{{10, 0.1},  {10, 0.07}, {10, 0.05}, {20, 0.1}, {20, 0.07},
                                                            {20, 0.05}, {40, 0.1},  {40, 0.07}, {40, 0.05}};
  const std::string path = CONTACTQP_SOURCE_DIR "/scenes/punch.json";
  const std::string text = read_text(path);
  for (const Case& c : cases) {
    Scene scene = parse_scene(text, path);
    scene.body.width = scene.body.depth = scene.body.height = c.block;
    scene.body.mesh.contact_size = c.contact_size;
    scene.body.mesh.size = c.block / 10;
    const Run r = run(scene);
    const auto punch = compare_with_boussinesq(r.model, r.contact);
    csv << c.block << ',' << c.contact_size << ',' << scene.body.mesh.size << ',' << r.model.mesh.n_nodes() << ','
        << r.model.mesh.n_elements() << ',' << r.qp.n_dofs() << ',' << r.qp.n_constraints() << ','
        << to_string(r.result.status) << ',' << r.result.iterations << ',' << r.contact.total_force << ','
        << (punch ? punch->force : NAN) << ',' << (punch ? punch->error_force : NAN) << ','
        << (punch ? punch->shape_error : NAN) << ',' << r.seconds << '\n';
    std::cout << "punch block " << c.block << " contact_size " << c.contact_size << ": " << r.qp.n_dofs()
              << " DOFs, force error " << (punch ? 100 * punch->error_force : NAN) << "%, " << r.seconds << " s"
              << std::endl;
  }
}

}  // namespace

int main(int argc, char** argv) {
  bench::OutArguments arguments;
  if (!bench::parse_out_arguments(argc, argv, "hertz3d", arguments)) return 2;
  try {
    std::ostringstream sphere, punch;
    sphere.precision(10);
    punch.precision(10);
    sphere_study(arguments.quick, sphere);
    punch_study(arguments.quick, punch);
    write_file_atomically(bench::output_path(arguments.out, "sphere.csv"), sphere.str());
    write_file_atomically(bench::output_path(arguments.out, "punch.csv"), punch.str());
    write_file_atomically(
        arguments.out + "/context.json",
        bench::context_json("hertz3d", R"({"scenes": ["scenes/hertz-sphere.json", "scenes/punch.json"]})"));
    std::cout << "wrote sphere.csv, punch.csv and context.json in " << arguments.out << "\n";
  } catch (const InputError& error) {
    std::cerr << "bench_hertz3d: " << error.what() << "\n";
    return 2;
  }
  return 0;
}
