// benchmarks/scaling/factor_prediction: how big CHOLMOD's factor of K would be, from its
// symbolic analysis alone, on meshes too large to factorise here. For each scene: mesh,
// assemble, analyse K (the scene's ordering, METIS in 3D) and write nnz(L), the bytes that
// factorising would allocate for L, the flops, and the peak resident memory of this process
// (mesh + K, what a solve would hold before the factor). On sizes that do fit, nnz(L) equals
// the factor_nonzeros that scaling_benchmark measured (the same analysis), which checks the
// prediction. Writes factor-prediction.csv (docs/3d.md, "Where the time and memory go").
#include <CLI/CLI.hpp>
#include <fstream>
#include <iostream>
#include <sstream>

#include "contactqp/cholesky.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/io.hpp"
#include "contactqp/model.hpp"
#include "contactqp/number_format.hpp"
#include "contactqp/timer.hpp"
#include "context.hpp"
#include "hertz_levels.hpp"

using namespace contactqp;
using namespace contactqp::bench;

namespace {

// VmHWM of this process in MiB: the peak resident memory so far (NaN when unreadable).
double peak_rss_mib() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return NAN;
}

struct Arguments {
  std::string scenes;
  std::string out;
};

int run(const Arguments& arguments) {
  require(!arguments.scenes.empty(), "--scenes", arguments.scenes, "must name at least one scene file");
  make_directory(arguments.out);
  std::string csv =
      "scene,order,contact_size,nodes,elements,dofs,constraints,k_nonzeros,ordering,supernodal,factor_nonzeros,"
      "factor_gib,fits_32bit_indices,flops,analyse_seconds,mesh_seconds,assemble_seconds,peak_rss_mib\n";
  std::stringstream list(arguments.scenes);
  std::string path;
  while (std::getline(list, path, ',')) {
    const Scene scene = load_scene(path);
    QuadraticProgram qp;
    Model model = build_model(scene);
    qp = assemble_qp(model);
    const FactorPrediction p = CholeskyFactor::predict(qp.K, scene.solver.ordering);
    if (!p.ok) throw std::runtime_error(path + ": " + p.message);
    // The scene relative to the source tree when it lies there, so that the CSV is portable.
    const std::string source_dir = CONTACTQP_SOURCE_DIR "/";
    const std::string name = path.rfind(source_dir, 0) == 0 ? path.substr(source_dir.size()) : path;
    const std::string line = name + "," + std::to_string(model.mesh.order) + "," +
                             csv_number(scene.body.mesh.contact_size) + "," + std::to_string(model.mesh.n_nodes()) +
                             "," + std::to_string(model.mesh.n_elements()) + "," + std::to_string(qp.n_dofs()) + "," +
                             std::to_string(qp.n_constraints()) + "," + std::to_string(qp.K.nonZeros()) + "," +
                             p.ordering + "," + (p.supernodal ? "1" : "0") + "," + std::to_string(p.factor_nonzeros) +
                             "," + csv_number(p.factor_bytes / (1024.0 * 1024.0 * 1024.0), 6) + "," +
                             (p.fits_32bit_indices ? "1" : "0") + "," + csv_number(p.flops, 6) + "," +
                             csv_number(p.analyse_seconds, 6) + "," + csv_number(model.timings.get("mesh"), 6) + "," +
                             csv_number(model.timings.get("assemble"), 6) + "," + csv_number(peak_rss_mib(), 6) + "\n";
    std::cout << line << std::flush;
    csv += line;
    write_file_atomically(arguments.out + "/factor-prediction.csv", csv);
  }
  write_file_atomically(arguments.out + "/factor-prediction-context.json",
                        context_json("factor_prediction", "{\"scenes\": \"" + arguments.scenes + "\"}"));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"CHOLMOD's predicted factor size (symbolic analysis only) for the given scenes"};
  Arguments arguments;
  app.add_option("--scenes", arguments.scenes, "Comma-separated scene files")->required();
  app.add_option("--out", arguments.out, "Directory for factor-prediction.csv")->required();
  CLI11_PARSE(app, argc, argv);
  try {
    return run(arguments);
  } catch (const InputError& error) {
    std::cerr << "factor_prediction: error: " << error.what() << "\n";
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "factor_prediction: error: " << error.what() << "\n";
    return 1;
  }
}
