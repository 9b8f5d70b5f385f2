// bench_rho: Uzawa's step ρ on Hertz scenes of several mesh sizes (docs/rho.md).
//
// For each contact element size h (far field 50 h, as scenes/hertz.json has at h = 0.002 R)
// the scene is generated from scenes/hertz.json, K is factored once, and
//   - a tight solve (tol 1e-12) gives the reference λ,
//   - --rho auto is run with plain and accelerated Uzawa          -> auto.csv
//   - ρ/ρ_max is swept log-spaced over [0.01, 2.5], both variants -> sweep.csv
//   - S = B K⁻¹ Bᵀ is formed densely once (an independent check of the Lanczos estimate) and
//     its spectrum on the working set, the active set and all rows is recorded -> meshes.csv
// The sweep caps each run at cap_factor × the iterations of plain Uzawa at auto ρ; a capped
// run is a row with status max_iterations, like a diverged run is a row with status diverged.
// plot.py draws the figures from these CSVs alone.
#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "contactqp/backends/uzawa.hpp"
#include "contactqp/cholesky.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/io.hpp"
#include "contactqp/model.hpp"
#include "contactqp/number_format.hpp"
#include "contactqp/solve.hpp"
#include "context.hpp"
#include "qp/dense_decompositions.hpp"

using namespace contactqp;

namespace {

struct Settings {
  std::string scene = CONTACTQP_SOURCE_DIR "/scenes/hertz.json";
  std::string out = CONTACTQP_SOURCE_DIR "/benchmarks/rho/results";
  std::vector<double> contact_sizes = {0.008, 0.004, 0.002, 0.001};
  double far_field_ratio = 50;  // far-field size / contact size
  int points = 31;
  double cap_factor = 3;
  double tol = 1e-8;
  bool smoke = false;
};

const char* const kHeader = "rho,rho_over_rho_max,mesh_size,dofs,variant,iterations,seconds,status,rel_error_lambda\n";

struct Mesh {
  double contact_size = 0;
  QuadraticProgram qp;
  std::shared_ptr<const CholeskyFactor> factor;
  VectorXd lambda_reference;
};

SolveOptions options_for(const Mesh& mesh, Backend backend, double tol, int max_iterations) {
  SolveOptions options;
  options.backend = backend;
  options.tol = tol;
  options.max_iterations = max_iterations;
  options.K_factor = mesh.factor;
  return options;
}

// One run as a CSV row; `iterations` receives the count for the caller.
std::string run_row(const Mesh& mesh, const SolveOptions& options, int* iterations = nullptr) {
  Stopwatch clock;
  const SolveResult r = solve(mesh.qp, options);
  const double seconds = clock.seconds();
  if (iterations) *iterations = r.iterations;
  const double rho = r.diagnostics.count("rho") ? r.diagnostics.at("rho") : 0.0;
  const double rho_max = r.diagnostics.count("rho_max") ? r.diagnostics.at("rho_max") : 0.0;
  const double error = (r.lambda - mesh.lambda_reference).norm() / mesh.lambda_reference.norm();
  return csv_number(rho) + "," + csv_number(rho_max > 0 ? rho / rho_max : 0.0) + "," + csv_number(mesh.contact_size) +
         "," + std::to_string(mesh.qp.n_dofs()) + "," + to_string(options.backend) + "," +
         std::to_string(r.iterations) + "," + csv_number(seconds) + "," + to_string(r.status) + "," +
         csv_number(error) + "\n";
}

// Extreme eigenvalues of the principal block of the dense S on `rows`.
std::pair<double, double> block_spectrum(const Eigen::MatrixXd& S, const std::vector<int>& rows) {
  if (rows.empty()) return {0.0, 0.0};
  Eigen::MatrixXd block(rows.size(), rows.size());
  for (size_t i = 0; i < rows.size(); ++i)
    for (size_t j = 0; j < rows.size(); ++j) block(i, j) = S(rows[i], rows[j]);
  const Eigen::VectorXd values =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(block, Eigen::EigenvaluesOnly).eigenvalues();
  return {values.minCoeff(), values.maxCoeff()};
}

std::vector<double> log_spaced(double from, double to, int points) {
  std::vector<double> values;
  for (int i = 0; i < points; ++i)
    values.push_back(from * std::pow(to / from, points > 1 ? double(i) / (points - 1) : 0.0));
  return values;
}

int run(const Settings& settings) {
  std::filesystem::create_directories(settings.out);
  const std::string sweep_path = settings.out + "/sweep.csv", auto_path = settings.out + "/auto.csv",
                    meshes_path = settings.out + "/meshes.csv", context_path = settings.out + "/context.json";
  for (const std::string& path : {sweep_path, auto_path, meshes_path, context_path}) check_output_path(path, "--out");
  std::ifstream scene_file(settings.scene);
  if (!scene_file) throw InputError("--scene", "= " + settings.scene + ": cannot be read");
  const nlohmann::json base_scene = nlohmann::json::parse(scene_file);

  std::string sweep_csv = kHeader, auto_csv = kHeader;
  std::string meshes_csv =
      "mesh_size,far_field_size,dofs,constraints,working_rows,active_rows,lambda_min_S,lambda_max_S,spectrum_rows,"
      "spectrum_solves,spectrum_seconds,lambda_min_working,lambda_max_working,lambda_min_active,lambda_max_active,"
      "lambda_min_all,lambda_max_all,rho_max,rho_opt,max_iterations,factorize_seconds,one_solve_seconds,"
      "reference_iterations,reference_accelerated_rel_diff_lambda\n";
  Stopwatch total;
  for (const double h : settings.contact_sizes) {
    nlohmann::json scene_json = base_scene;
    scene_json["body"]["mesh"]["contact_size"] = h;
    scene_json["body"]["mesh"]["size"] = settings.far_field_ratio * h;
    Model model = build_model(parse_scene(scene_json.dump(), settings.scene + " (contact_size " + csv_number(h) + ")"));
    Mesh mesh;
    mesh.contact_size = h;
    mesh.qp = assemble_qp(model);
    const QuadraticProgram& qp = mesh.qp;

    Stopwatch clock;
    mesh.factor = std::make_shared<const CholeskyFactor>(qp.K);
    const double factorize_seconds = clock.seconds();
    if (!mesh.factor->ok()) throw std::runtime_error("K could not be factorised: " + mesh.factor->message());
    clock.restart();
    const int n_timed = 20;
    for (int i = 0; i < n_timed; ++i) mesh.factor->solve(qp.f);
    const double one_solve_seconds = clock.seconds() / n_timed;

    // The reference: plain Uzawa at a tight tolerance, checked against the accelerated variant.
    const SolveResult reference = solve(qp, options_for(mesh, Backend::Uzawa, 1e-12, 1'000'000));
    if (reference.status != Status::Converged) throw std::runtime_error("reference solve: " + reference.message);
    mesh.lambda_reference = reference.lambda;
    const SolveResult check = solve(qp, options_for(mesh, Backend::UzawaAccelerated, 1e-12, 1'000'000));
    const double reference_diff = (check.lambda - reference.lambda).norm() / reference.lambda.norm();

    int auto_iterations = 0, auto_accelerated = 0;
    auto_csv += run_row(mesh, options_for(mesh, Backend::Uzawa, settings.tol, 1'000'000), &auto_iterations);
    auto_csv += run_row(mesh, options_for(mesh, Backend::UzawaAccelerated, settings.tol, 1'000'000), &auto_accelerated);
    const int cap = static_cast<int>(settings.cap_factor * auto_iterations);

    int best_plain = 0;
    double best_fraction = 0;
    for (const Backend backend : {Backend::Uzawa, Backend::UzawaAccelerated}) {
      for (const double fraction : log_spaced(0.01, 2.5, settings.points)) {
        SolveOptions options = options_for(mesh, backend, settings.tol, cap);
        options.set(UzawaOptions{UzawaOptions::RhoRule::FractionOfMax, fraction});
        int iterations = 0;
        const std::string row = run_row(mesh, options, &iterations);
        sweep_csv += row;
        if (backend == Backend::Uzawa && row.find(",converged,") != std::string::npos &&
            (best_plain == 0 || iterations < best_plain)) {
          best_plain = iterations;
          best_fraction = fraction;
        }
      }
    }

    // The dense S = B K⁻¹ Bᵀ: the truth for the Lanczos estimate and the prediction's spectrum.
    const Eigen::MatrixXd S = Eigen::MatrixXd(qp.B) * mesh.factor->solve_columns(Eigen::MatrixXd(qp.B.transpose()));
    const VectorXd violation = qp.B * mesh.factor->solve(qp.f) - qp.g;
    std::vector<int> working, active, all;
    for (int i = 0; i < qp.n_constraints(); ++i) {
      all.push_back(i);
      if (violation[i] > 0) working.push_back(i);
      if (reference.lambda[i] > 0) active.push_back(i);
    }
    const auto [w_min, w_max] = block_spectrum(S, working);
    const auto [a_min, a_max] = block_spectrum(S, active);
    const auto [all_min, all_max] = block_spectrum(S, all);
    const auto& d = reference.diagnostics;
    meshes_csv += csv_number(h) + "," + csv_number(settings.far_field_ratio * h) + "," + std::to_string(qp.n_dofs()) +
                  "," + std::to_string(qp.n_constraints()) + "," + std::to_string(working.size()) + "," +
                  std::to_string(active.size()) + "," + csv_number(d.at("lambda_min_S")) + "," +
                  csv_number(d.at("lambda_max_S")) + "," + csv_number(d.at("spectrum_rows")) + "," +
                  csv_number(d.at("spectrum_solves")) + "," + csv_number(reference.timings.get("spectrum")) + "," +
                  csv_number(w_min) + "," + csv_number(w_max) + "," + csv_number(a_min) + "," + csv_number(a_max) +
                  "," + csv_number(all_min) + "," + csv_number(all_max) + "," + csv_number(d.at("rho_max")) + "," +
                  csv_number(d.at("rho_opt")) + "," + std::to_string(cap) + "," + csv_number(factorize_seconds) + "," +
                  csv_number(one_solve_seconds) + "," + std::to_string(reference.iterations) + "," +
                  csv_number(reference_diff) + "\n";
    std::cout << "h = " << h << ": " << qp.n_dofs() << " DOFs, " << qp.n_constraints() << " candidates, "
              << active.size() << " active; uzawa auto " << auto_iterations << " iterations, best of sweep "
              << best_plain << " at " << csv_number(best_fraction) << " rho_max, uzawa_accel auto " << auto_accelerated
              << " (" << std::fixed << std::setprecision(1) << total.seconds() << std::defaultfloat << " s so far)"
              << std::endl;
  }
  write_file_atomically(sweep_path, sweep_csv);
  write_file_atomically(auto_path, auto_csv);
  write_file_atomically(meshes_path, meshes_csv);
  // The scene relative to the source tree when it lies there, so that the context is portable.
  const std::string source_dir = CONTACTQP_SOURCE_DIR "/";
  const std::string scene =
      settings.scene.rfind(source_dir, 0) == 0 ? settings.scene.substr(source_dir.size()) : settings.scene;
  nlohmann::json extra = {{"scene", scene},
                          {"points", settings.points},
                          {"cap_factor", settings.cap_factor},
                          {"tol", settings.tol},
                          {"far_field_ratio", settings.far_field_ratio},
                          {"contact_sizes", settings.contact_sizes},
                          {"seconds", total.seconds()}};
  write_file_atomically(context_path, bench::context_json("rho", extra.dump()));
  std::cout << "wrote " << sweep_path << ", " << auto_path << ", " << meshes_path << ", " << context_path << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Settings settings;
  CLI::App app{"bench_rho: Uzawa's step rho on Hertz scenes of several mesh sizes"};
  app.add_option("--scene", settings.scene, "Scene the meshes are generated from");
  app.add_option("--out", settings.out, "Directory for sweep.csv, auto.csv, meshes.csv, context.json");
  app.add_option("--contact-sizes", settings.contact_sizes, "Element sizes along the contact arc")->delimiter(',');
  app.add_option("--far-field-ratio", settings.far_field_ratio, "Far-field size over contact size");
  app.add_option("--points", settings.points, "Points of the sweep over rho/rho_max in [0.01, 2.5]");
  app.add_option("--cap-factor", settings.cap_factor, "Iteration cap of a sweep run, times plain Uzawa's at auto rho");
  app.add_option("--tol", settings.tol, "Tolerance of every run but the reference");
  app.add_flag("--smoke", settings.smoke, "One coarse mesh and five points: checks that the benchmark runs");
  CLI11_PARSE(app, argc, argv);
  if (settings.smoke) {
    settings.contact_sizes = {0.008};
    settings.points = 5;
  }
  try {
    return run(settings);
  } catch (const InputError& error) {
    std::cerr << "bench_rho: error: " << error.what() << "\n";
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "bench_rho: error: " << error.what() << "\n";
    return 1;
  }
}
