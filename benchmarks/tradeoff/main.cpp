// bench_tradeoff: what each digit of accuracy costs, per backend and per mesh, on Hertz's
// cylinder (docs/tradeoff.md).
//
// For each contact element size h the scene is generated from scenes/hertz.json by scaling its
// size and contact_size together (far field = the scene's ratio × h); the model and the QP are
// built once per mesh, and every available backend is run on that QP at every tolerance, from
// scratch (its own factorisation of K included, as `contactqp compare` does). Per run, runs.csv
// records the solve time, the certificate, the errors against Hertz (b, p0, L2 pressure) and
// the relative errors in u and λ against the mesh's reference: the converged run at the tightest
// tolerance with the smallest certified |duality gap| (ties: the smallest KKT residual), as
// `contactqp compare` chooses. meshes.csv has one row per mesh: meshing, model, assembly,
// factorisation and one solve, measured once per mesh; the reference and its errors; the L2
// difference of its pressure from the finest mesh's (the discretisation error); and, with
// --peer-meshes, the check that GetFEM's mesh file is this mesh.
//
// Time cap: a run slower than --time-cap ends that backend's sweep on that mesh (its tighter
// tolerances are rows with status "skipped" and the reason), and a tolerance skipped or over the
// cap on a mesh is skipped on the finer ones. Runs faster than --repeat-below are repeated up
// to --repeat times and the fastest is kept (the machine may be shared).
// plot.py draws the figures and the README tables from these CSVs alone.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "contactqp/certificate.hpp"
#include "contactqp/cholesky.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/io.hpp"
#include "contactqp/model.hpp"
#include "contactqp/number_format.hpp"
#include "contactqp/post.hpp"
#include "contactqp/solve.hpp"
#include "context.hpp"
#include "peer_mesh.hpp"
#include "pressure_difference.hpp"
#include "qp/norms.hpp"

using namespace contactqp;

namespace {

struct Settings {
  std::string scene = CONTACTQP_SOURCE_DIR "/scenes/hertz.json";
  std::string out = CONTACTQP_SOURCE_DIR "/benchmarks/tradeoff/results";
  std::vector<double> contact_sizes = {0.016, 0.008, 0.004, 0.002, 0.001, 0.0005};
  std::vector<double> tolerances = {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
  std::string backends;  // comma-separated; empty: every available backend
  double time_cap_seconds = 60;
  int repeat = 3;
  double repeat_below_seconds = 1;
  int max_iterations = 1'000'000;
  std::string peer_meshes;  // directory with GetFEM's mesh_o1_cs<h>.msh files, or empty
  bool smoke = false;
};

const char* const kRunsHeader =
    "contact_size,dofs,backend,tol,status,iterations,seconds,repeats,seconds_over_one_solve,kkt_max,"
    "relative_gap,total_force,half_width,max_pressure,error_b,error_p0,error_l2,rel_error_u,rel_error_lambda,"
    "reference,message\n";
const char* const kMeshesHeader =
    "contact_size,size,nodes,triangles,dofs,constraints,mesh_seconds,model_seconds,assemble_seconds,"
    "factorize_seconds,one_solve_seconds,reference_backend,reference_tol,reference_relative_gap,reference_kkt_max,"
    "reference_spread_u,reference_spread_lambda,total_force,half_width,max_pressure,contact_nodes,error_b,error_p0,"
    "error_l2,l2_difference_to_finest,peer_msh,peer_same_mesh,peer_nodes,peer_triangles,peer_dofs,peer_constraints,"
    "peer_max_node_distance\n";

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return out + "\"";
}

std::string percent(double x) { return format("%+.2f%%", 100 * x); }

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

// One backend at one tolerance on one mesh.
struct Run {
  Backend backend;
  double tol = 0;
  bool skipped = false;
  std::string message;  // the backend's, or why the run was skipped
  Status status = Status::NumericalError;
  int iterations = 0, repeats = 0;
  double seconds = kNone;
  Certificate certificate;
  ContactSummary contact;
  std::optional<HertzComparison> hertz;
  VectorXd u, lambda;
};

std::string status_name(const Run& run) { return run.skipped ? "skipped" : to_string(run.status); }

// The mesh's reference among `runs`: converged at the tightest tolerance that has a converged
// run, smallest certified |relative gap|, then smallest KKT residual. -1 when none converged.
int choose_reference(const std::vector<Run>& runs) {
  int best = -1;
  for (int i = 0; i < static_cast<int>(runs.size()); ++i) {
    const Run& r = runs[i];
    if (r.skipped || r.status != Status::Converged || !r.certificate.dual_available) continue;
    if (best >= 0) {
      const Run& b = runs[best];
      if (r.tol != b.tol) {
        if (r.tol > b.tol) continue;
      } else {
        const double gap = std::abs(r.certificate.relative_gap), best_gap = std::abs(b.certificate.relative_gap);
        if (gap > best_gap || (gap == best_gap && r.certificate.kkt_max() >= b.certificate.kkt_max())) continue;
      }
    }
    best = i;
  }
  return best;
}

std::vector<Backend> parse_backend_list(const std::string& text) {
  if (text.empty()) return available_backends();
  std::vector<Backend> backends;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    backends.push_back(parse_backend(text.substr(start, comma - start), "--backends"));
    start = comma + 1;
  }
  return backends;
}

void validate(const Settings& s) {
  require(!s.contact_sizes.empty(), "--contact-sizes", "", "must name at least one size");
  for (double h : s.contact_sizes) require(h > 0, "--contact-sizes", h, "must be positive");
  require(!s.tolerances.empty(), "--tolerances", "", "must name at least one tolerance");
  for (double tol : s.tolerances) require(tol > 0 && tol < 1, "--tolerances", tol, "must lie in (0, 1)");
  require(s.time_cap_seconds > 0, "--time-cap", s.time_cap_seconds, "must be positive");
  require(s.repeat >= 1, "--repeat", s.repeat, "must be at least 1");
  require(s.max_iterations >= 1, "--max-iterations", s.max_iterations, "must be at least 1");
}

// One mesh: the model and QP built once, every backend at every tolerance on it.
struct MeshStudy {
  double contact_size = 0, size = 0;
  Model model;
  QuadraticProgram qp;
  double assemble_seconds = 0, factorize_seconds = 0, one_solve_seconds = 0;
  std::vector<Run> runs;
  int reference = -1;
  std::optional<bench::PeerMeshCheck> peer;
};

class Study {
 public:
  explicit Study(const Settings& settings) : settings_(settings) {}
  int run();

 private:
  void run_mesh(MeshStudy& mesh, int mesh_index);
  Run run_one(const MeshStudy& mesh, Backend backend, double tol);
  void progress(const MeshStudy& mesh, const Run& run);
  std::string runs_rows(const MeshStudy& mesh) const;
  std::string mesh_row(const MeshStudy& mesh, double difference_to_finest) const;

  Settings settings_;
  std::vector<Backend> backends_;
  nlohmann::json base_scene_;
  std::vector<double> sizes_;  // coarse to fine
  int runs_total_ = 0, runs_done_ = 0;
  Stopwatch clock_;
  // (backend, tol) skipped or over the cap on a coarser mesh: skipped on the finer ones too.
  std::map<std::pair<Backend, double>, std::string> capped_;
};

Run Study::run_one(const MeshStudy& mesh, Backend backend, double tol) {
  Run run;
  run.backend = backend;
  run.tol = tol;
  SolveOptions options;
  options.backend = backend;
  options.tol = tol;
  options.max_iterations = settings_.max_iterations;
  SolveResult result;
  for (run.repeats = 0; run.repeats < settings_.repeat;) {
    Stopwatch clock;
    result = solve(mesh.qp, options);
    const double seconds = clock.seconds();
    ++run.repeats;
    run.seconds = run.repeats == 1 ? seconds : std::min(run.seconds, seconds);
    if (seconds >= settings_.repeat_below_seconds) break;
  }
  run.status = result.status;
  run.message = result.message;
  run.iterations = result.iterations;
  run.u = std::move(result.u);
  run.lambda = std::move(result.lambda);
  return run;
}

void Study::progress(const MeshStudy& mesh, const Run& run) {
  std::string line = "tradeoff [" + std::to_string(runs_done_) + "/" + std::to_string(runs_total_) + ", " +
                     number(clock_.seconds()) + " s] h " + number(mesh.contact_size) + " (" +
                     std::to_string(mesh.qp.n_dofs()) + " DOFs) " + to_string(run.backend) + " tol " + number(run.tol) +
                     ": " + status_name(run);
  if (run.skipped) {
    line += " (" + run.message + ")";
  } else {
    char timing[96];
    std::snprintf(timing, sizeof timing, ", %d it., %.4g s (fastest of %d)", run.iterations, run.seconds, run.repeats);
    line += timing;
    if (run.hertz)
      line += "; b " + percent(run.hertz->error_half_width) + ", p0 " + percent(run.hertz->error_max_pressure) +
              ", L2 " + percent(run.hertz->error_l2).substr(1);
  }
  std::cerr << line << std::endl;
}

void Study::run_mesh(MeshStudy& mesh, int mesh_index) {
  const double h = mesh.contact_size;
  nlohmann::json scene_json = base_scene_;
  scene_json["body"]["mesh"]["contact_size"] = h;
  scene_json["body"]["mesh"]["size"] = mesh.size;
  mesh.model = build_model(parse_scene(scene_json.dump(), settings_.scene + " (contact_size " + number(h) + ")"));
  // Assembly is cheap and noisy: the fastest of a few, like the runs.
  for (int k = 0; k < 3; ++k) {
    Stopwatch clock;
    mesh.qp = assemble_qp(mesh.model);
    mesh.assemble_seconds = k == 0 ? clock.seconds() : std::min(mesh.assemble_seconds, clock.seconds());
  }
  // The unit of cost: one factorisation of K and one solve with it; the factor also certifies.
  Stopwatch clock;
  const CholeskyFactor factor(mesh.qp.K);
  mesh.factorize_seconds = clock.seconds();
  if (!factor.ok()) throw std::runtime_error("K could not be factorised: " + factor.message());
  mesh.one_solve_seconds = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 5; ++k) {
    clock.restart();
    factor.solve(mesh.qp.f);
    mesh.one_solve_seconds = std::min(mesh.one_solve_seconds, clock.seconds());
  }
  std::cerr << "tradeoff mesh " << mesh_index + 1 << "/" << sizes_.size() << ": contact_size " << number(h) << ", size "
            << number(mesh.size) << ": " << mesh.model.mesh.n_nodes() << " nodes, " << mesh.qp.n_dofs() << " DOFs, "
            << mesh.qp.n_constraints() << " candidates; mesh " << number(mesh.model.timings.get("mesh"))
            << " s, assembly " << number(mesh.assemble_seconds) << " s, factorisation "
            << number(mesh.factorize_seconds) << " s, one solve " << number(mesh.one_solve_seconds) << " s"
            << std::endl;

  if (!settings_.peer_meshes.empty()) {
    const std::string msh =
        (std::filesystem::absolute(settings_.peer_meshes) / ("mesh_o1_cs" + number(h) + ".msh")).string();
    if (std::filesystem::exists(msh))
      mesh.peer = bench::check_peer_mesh(scene_json, msh, mesh.model.mesh);
    else
      std::cerr << "tradeoff: warning: no peer mesh " << msh << "\n";
  }

  for (const Backend backend : backends_) {
    std::string cap_reason;
    for (const double tol : settings_.tolerances) {
      Run run;
      const auto key = std::make_pair(backend, tol);
      if (cap_reason.empty() && capped_.count(key)) cap_reason = capped_.at(key);
      if (!cap_reason.empty()) {
        run.backend = backend;
        run.tol = tol;
        run.skipped = true;
        run.message = cap_reason;
        capped_[key] = cap_reason;
      } else {
        run = run_one(mesh, backend, tol);
        run.certificate = certify(mesh.qp, run.u, run.lambda, &factor);
        run.contact = summarize_contact(mesh.model, mesh.qp, run.u, run.lambda);
        run.hertz = compare_with_hertz(mesh.model, run.contact);
        if (run.seconds > settings_.time_cap_seconds) {
          cap_reason = "time cap: tol " + number(tol) + " took " + number(run.seconds) + " s > " +
                       number(settings_.time_cap_seconds) + " s on contact_size " + number(h);
          capped_[key] = cap_reason;
        }
      }
      ++runs_done_;
      progress(mesh, run);
      mesh.runs.push_back(std::move(run));
    }
  }
  mesh.reference = choose_reference(mesh.runs);
  if (mesh.reference >= 0) {
    const Run& ref = mesh.runs[mesh.reference];
    std::cerr << "tradeoff mesh " << mesh_index + 1 << ": reference " << to_string(ref.backend) << " at tol "
              << number(ref.tol) << " (relative gap " << number(ref.certificate.relative_gap) << ", KKT "
              << number(ref.certificate.kkt_max()) << ")" << std::endl;
  } else {
    std::cerr << "tradeoff mesh " << mesh_index + 1 << ": no converged run, no reference" << std::endl;
  }
}

std::string Study::runs_rows(const MeshStudy& mesh) const {
  std::string rows;
  const Run* ref = mesh.reference >= 0 ? &mesh.runs[mesh.reference] : nullptr;
  for (size_t i = 0; i < mesh.runs.size(); ++i) {
    const Run& r = mesh.runs[i];
    const bool solved = !r.skipped;
    const Certificate& c = r.certificate;
    const auto hertz = [&](double HertzComparison::*field) {
      return solved && r.hertz ? csv_number((*r.hertz).*field) : "";
    };
    const auto solved_number = [&](double x) { return solved ? csv_number(x) : ""; };
    rows += csv_number(mesh.contact_size) + "," + std::to_string(mesh.qp.n_dofs()) + "," + to_string(r.backend) + "," +
            csv_number(r.tol) + "," + status_name(r) + "," + (solved ? std::to_string(r.iterations) : "") + "," +
            solved_number(r.seconds) + "," + (solved ? std::to_string(r.repeats) : "") + "," +
            solved_number(r.seconds / mesh.one_solve_seconds) + "," + solved_number(c.kkt_max()) + "," +
            (solved && c.dual_available ? csv_number(c.relative_gap) : "") + "," +
            solved_number(r.contact.total_force) + "," + solved_number(r.contact.half_width) + "," +
            solved_number(r.contact.max_pressure) + "," + hertz(&HertzComparison::error_half_width) + "," +
            hertz(&HertzComparison::error_max_pressure) + "," + hertz(&HertzComparison::error_l2) + "," +
            (solved && ref ? csv_number(relative_difference(r.u, ref->u)) : "") + "," +
            (solved && ref ? csv_number(relative_difference(r.lambda, ref->lambda)) : "") + "," +
            (static_cast<int>(i) == mesh.reference ? "1" : "0") + "," + quoted(r.message) + "\n";
  }
  return rows;
}

std::string Study::mesh_row(const MeshStudy& mesh, double difference_to_finest) const {
  const Run* ref = mesh.reference >= 0 ? &mesh.runs[mesh.reference] : nullptr;
  // How far the other converged runs at the reference's tolerance lie from it: the reference's
  // own uncertainty, the floor of the relative errors.
  double spread_u = kNone, spread_lambda = kNone;
  if (ref)
    for (const Run& r : mesh.runs)
      if (&r != ref && !r.skipped && r.status == Status::Converged && r.tol == ref->tol) {
        spread_u = std::isfinite(spread_u) ? std::max(spread_u, relative_difference(r.u, ref->u))
                                           : relative_difference(r.u, ref->u);
        const double dl = relative_difference(r.lambda, ref->lambda);
        spread_lambda = std::isfinite(spread_lambda) ? std::max(spread_lambda, dl) : dl;
      }
  const auto of_ref = [&](double x) { return ref ? csv_number(x) : ""; };
  const auto hertz = [&](double HertzComparison::*field) {
    return ref && ref->hertz ? csv_number((*ref->hertz).*field) : "";
  };
  std::string row =
      csv_number(mesh.contact_size) + "," + csv_number(mesh.size) + "," + std::to_string(mesh.model.mesh.n_nodes()) +
      "," + std::to_string(mesh.model.mesh.n_elements()) + "," + std::to_string(mesh.qp.n_dofs()) + "," +
      std::to_string(mesh.qp.n_constraints()) + "," + csv_number(mesh.model.timings.get("mesh")) + "," +
      csv_number(mesh.model.timings.get("model")) + "," + csv_number(mesh.assemble_seconds) + "," +
      csv_number(mesh.factorize_seconds) + "," + csv_number(mesh.one_solve_seconds) + "," +
      (ref ? to_string(ref->backend) : "") + "," + of_ref(ref ? ref->tol : kNone) + "," +
      of_ref(ref ? ref->certificate.relative_gap : kNone) + "," + of_ref(ref ? ref->certificate.kkt_max() : kNone) +
      "," + csv_number(spread_u) + "," + csv_number(spread_lambda) + "," +
      of_ref(ref ? ref->contact.total_force : kNone) + "," + of_ref(ref ? ref->contact.half_width : kNone) + "," +
      of_ref(ref ? ref->contact.max_pressure : kNone) + "," + (ref ? std::to_string(ref->contact.contact_nodes) : "") +
      "," + hertz(&HertzComparison::error_half_width) + "," + hertz(&HertzComparison::error_max_pressure) + "," +
      hertz(&HertzComparison::error_l2) + "," + csv_number(difference_to_finest) + ",";
  if (mesh.peer) {
    const bench::PeerMeshCheck& p = *mesh.peer;
    const bool same = p.nodes == mesh.model.mesh.n_nodes() && p.triangles == mesh.model.mesh.n_elements() &&
                      p.dofs == mesh.qp.n_dofs() && p.constraints == mesh.qp.n_constraints() &&
                      p.max_node_distance <= 1e-12 * mesh.model.scene.body.radius;
    row += quoted(std::filesystem::path(p.file).filename().string()) + "," + (same ? "1" : "0") + "," +
           std::to_string(p.nodes) + "," + std::to_string(p.triangles) + "," + std::to_string(p.dofs) + "," +
           std::to_string(p.constraints) + "," + csv_number(p.max_node_distance);
  } else {
    row += ",,,,,,";
  }
  return row + "\n";
}

int Study::run() {
  validate(settings_);
  backends_ = parse_backend_list(settings_.backends);
  for (const Backend backend : backends_) {
    SolveOptions options;
    options.backend = backend;
    options.max_iterations = settings_.max_iterations;
    validate_options(options);
  }
  std::filesystem::create_directories(settings_.out);
  const std::string runs_path = settings_.out + "/runs.csv", meshes_path = settings_.out + "/meshes.csv",
                    context_path = settings_.out + "/context.json";
  for (const std::string& path : {runs_path, meshes_path, context_path}) check_output_path(path, "--out");
  std::ifstream scene_file(settings_.scene);
  if (!scene_file) throw InputError("--scene", "= " + settings_.scene + ": cannot be read");
  base_scene_ = nlohmann::json::parse(scene_file);
  const Scene base = parse_scene(base_scene_.dump(), settings_.scene);
  require(base.body.shape == "half_disc", "--scene", settings_.scene, "must be a half_disc scene (Hertz's cylinder)");
  const double far_field_ratio = base.body.mesh.size / base.body.mesh.contact_size;

  sizes_ = settings_.contact_sizes;
  std::sort(sizes_.begin(), sizes_.end(), std::greater<double>());
  sizes_.erase(std::unique(sizes_.begin(), sizes_.end()), sizes_.end());
  runs_total_ = static_cast<int>(sizes_.size() * backends_.size() * settings_.tolerances.size());
  std::sort(settings_.tolerances.begin(), settings_.tolerances.end(), std::greater<double>());  // loose to tight

  std::vector<MeshStudy> meshes(sizes_.size());
  for (size_t k = 0; k < sizes_.size(); ++k) {
    meshes[k].contact_size = sizes_[k];
    meshes[k].size = std::min(far_field_ratio * sizes_[k], base.body.radius);
    run_mesh(meshes[k], static_cast<int>(k));
  }

  // The discretisation error: each reference's pressure against the finest mesh's.
  const MeshStudy& finest = meshes.back();
  std::string runs_csv = kRunsHeader, meshes_csv = kMeshesHeader;
  for (const MeshStudy& mesh : meshes) {
    double difference = kNone;
    if (mesh.reference >= 0 && finest.reference >= 0)
      difference = bench::relative_l2_difference(mesh.runs[mesh.reference].contact.profile,
                                                 finest.runs[finest.reference].contact.profile);
    runs_csv += runs_rows(mesh);
    meshes_csv += mesh_row(mesh, difference);
  }
  write_file_atomically(runs_path, runs_csv);
  write_file_atomically(meshes_path, meshes_csv);

  const std::string source_dir = CONTACTQP_SOURCE_DIR "/";
  const std::string scene =
      settings_.scene.rfind(source_dir, 0) == 0 ? settings_.scene.substr(source_dir.size()) : settings_.scene;
  std::vector<std::string> backend_names;
  for (const Backend backend : backends_) backend_names.push_back(to_string(backend));
  const nlohmann::json extra = {
      {"scene", scene},
      {"contact_sizes", sizes_},
      {"far_field_ratio", far_field_ratio},
      {"tolerances", settings_.tolerances},
      {"backends", backend_names},
      {"time_cap_seconds", settings_.time_cap_seconds},
      {"repeat", settings_.repeat},
      {"repeat_below_seconds", settings_.repeat_below_seconds},
      {"max_iterations", settings_.max_iterations},
      {"timing",
       "seconds = wall time of solve() from scratch (each backend factorises K itself), the fastest of "
       "`repeats` runs; assembly, model and meshing per mesh in meshes.csv"},
      {"reference",
       "per mesh: the converged run at the tightest tolerance with the smallest certified |relative "
       "duality gap| (ties: smallest KKT residual)"},
      {"seconds", clock_.seconds()}};
  write_file_atomically(context_path, bench::context_json("tradeoff", extra.dump()));
  std::cerr << "tradeoff: " << runs_done_ << " runs on " << meshes.size() << " meshes in " << number(clock_.seconds())
            << " s; wrote " << runs_path << ", " << meshes_path << ", " << context_path << std::endl;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Settings settings;
  CLI::App app{"bench_tradeoff: time against accuracy for every backend, tolerance and mesh of Hertz's cylinder"};
  app.add_option("--scene", settings.scene,
                 "Half-disc scene the meshes are generated from (its size/contact_size ratio is kept)");
  app.add_option("--out", settings.out, "Directory for runs.csv, meshes.csv, context.json");
  app.add_option("--contact-sizes", settings.contact_sizes, "Element sizes along the contact arc")->delimiter(',');
  app.add_option("--tolerances", settings.tolerances, "Solver tolerances")->delimiter(',');
  app.add_option("--backends", settings.backends, "Comma-separated backends (default: every one built in)");
  app.add_option("--time-cap", settings.time_cap_seconds,
                 "Seconds: a slower run ends its backend's sweep on that mesh");
  app.add_option("--repeat", settings.repeat,
                 "Runs faster than --repeat-below are repeated up to this many times; the fastest counts");
  app.add_option("--repeat-below", settings.repeat_below_seconds, "Seconds, see --repeat");
  app.add_option("--max-iterations", settings.max_iterations, "Iteration limit of every run");
  app.add_option("--peer-meshes", settings.peer_meshes,
                 "Directory with GetFEM's mesh_o1_cs<h>.msh: check they are these meshes");
  app.add_flag("--smoke", settings.smoke,
               "One coarse mesh, two tolerances, no repeats: checks that the benchmark runs");
  CLI11_PARSE(app, argc, argv);
  if (settings.smoke) {
    settings.contact_sizes = {0.016};
    settings.tolerances = {1e-3, 1e-8};
    settings.repeat = 1;
  }
  try {
    return Study(settings).run();
  } catch (const InputError& error) {
    std::cerr << "bench_tradeoff: error: " << error.what() << "\n";
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "bench_tradeoff: error: " << error.what() << "\n";
    return 1;
  }
}
