// benchmarks/scaling: every available backend on Hertz meshes from 1e3 to 1e6 DOFs, each
// timed against one linear solve of the same K in the same process.
//
// The parent meshes and assembles each level (meshing is timed but kept out of the solves),
// then forks one child per backend. The child first solves K u = f without the contact rows
// (solve_without_contact: same scaling, same factorisation and ordering), then the contact
// problem with a fresh factorisation, then the linear solve again (the faster of the two
// counts), and reports both; its peak memory is the kernel's
// high-water mark of resident memory (VmHWM), reset before each solve through
// /proc/self/clear_refs, so it counts the QP the solve was given plus everything the solve
// allocated. A child still running after --time-cap seconds is killed, and that backend is
// skipped on the larger meshes. Writes scaling.csv (one row per level and backend, fixed
// header), context.json and the scenes it generated; plot.py draws the figures from the CSV.
#include <malloc.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "contactqp/certificate.hpp"
#include "contactqp/cholesky.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/io.hpp"
#include "contactqp/model.hpp"
#include "contactqp/number_format.hpp"
#include "contactqp/solve.hpp"
#include "context.hpp"
#include "hertz_levels.hpp"

using namespace contactqp;
using namespace contactqp::bench;

namespace {

const char* const kHeader =
    "level,dofs,constraints,mesh_seconds,assemble_seconds,backend,status,iterations,"
    "factorize_seconds,condense_seconds,iterate_seconds,recover_seconds,solve_seconds,total_seconds,"
    "linear_factorize_seconds,linear_solve_seconds,linear_total_seconds,ratio_to_linear,"
    "peak_rss_mb,linear_peak_rss_mb,baseline_rss_mb,child_maxrss_mb,kkt_max,relative_gap,diff_u,diff_lambda,"
    "ordering,factor_nonzeros,phases,reason";

// A field of /proc/self/status in MiB ("VmRSS", "VmHWM"), or NaN when unreadable.
double status_mb(const std::string& field) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind(field + ":", 0) == 0) return std::stod(line.substr(field.size() + 1)) / 1024.0;
  return NAN;
}

// Resets VmHWM to the current resident size (Linux ≥ 4.0), so the next reading is the peak
// of what follows.
void reset_peak_memory() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
}

std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

// What one child reports: "key value" lines.
using Report = std::map<std::string, std::string>;

void write_vectors(const std::string& path, const VectorXd& u, const VectorXd& lambda) {
  std::ofstream file(path, std::ios::binary);
  for (const VectorXd* v : {&u, &lambda}) {
    const long long n = v->size();
    file.write(reinterpret_cast<const char*>(&n), sizeof n);
    file.write(reinterpret_cast<const char*>(v->data()), static_cast<std::streamsize>(sizeof(double) * n));
  }
}

bool read_vectors(const std::string& path, VectorXd& u, VectorXd& lambda) {
  std::ifstream file(path, std::ios::binary);
  for (VectorXd* v : {&u, &lambda}) {
    long long n = 0;
    if (!file.read(reinterpret_cast<char*>(&n), sizeof n) || n < 0) return false;
    v->resize(n);
    if (!file.read(reinterpret_cast<char*>(v->data()), static_cast<std::streamsize>(sizeof(double) * n))) return false;
  }
  return true;
}

// The child: linear solve, contact solve, certificate; reports on `fd`, writes u and λ.
[[noreturn]] void run_child(int fd, const QuadraticProgram& qp, const SolveOptions& options,
                            const std::string& vector_path) {
  std::ostringstream out;
  out.precision(10);
  int code = 0;
  try {
    out << "baseline_rss_mb " << status_mb("VmRSS") << "\n";
    // The linear solve runs before and after the contact solve and the faster run counts:
    // the first solve in a fresh process also pays for page faults and BLAS start-up.
    reset_peak_memory();
    SolveResult linear = solve_without_contact(qp, options);
    out << "linear_peak_rss_mb " << status_mb("VmHWM") << "\n";
    linear.K_factor.reset();
    ::malloc_trim(0);
    reset_peak_memory();
    const SolveResult result = solve(qp, options);
    out << "peak_rss_mb " << status_mb("VmHWM") << "\n";
    const SolveResult again = solve_without_contact(qp, options);
    const SolveResult& faster = again.timings.get("total") < linear.timings.get("total") ? again : linear;
    out << "linear_factorize_seconds " << faster.timings.get("factorize") << "\n"
        << "linear_solve_seconds " << faster.timings.get("solve") << "\n"
        << "linear_total_seconds " << faster.timings.get("total") << "\n";
    const Certificate certificate = certify(qp, result.u, result.lambda, result.K_factor.get());
    out << "status " << to_string(result.status) << "\n"
        << "message " << one_line(result.message) << "\n"
        << "iterations " << result.iterations << "\n"
        << "kkt_max " << certificate.kkt_max() << "\n"
        << "relative_gap " << certificate.relative_gap << "\n";
    if (result.K_factor) {
      out << "ordering " << result.K_factor->ordering_name() << "\n"
          << "factor_nonzeros " << result.K_factor->statistics().factor_nonzeros << "\n";
    }
    std::string phases;
    for (const auto& [phase, seconds] : result.timings.phases()) {
      out << "phase:" << phase << " " << seconds << "\n";
      std::ostringstream entry;
      entry.precision(6);
      entry << phase << "=" << seconds;
      phases += (phases.empty() ? "" : ";") + entry.str();
    }
    out << "phases " << phases << "\n";
    write_vectors(vector_path, result.u, result.lambda);
  } catch (const std::exception& error) {
    out << "status error\nmessage " << one_line(error.what()) << "\n";
    code = 1;
  }
  const std::string text = out.str();
  for (size_t written = 0; written < text.size();) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n <= 0) break;
    written += static_cast<size_t>(n);
  }
  ::close(fd);
  ::_exit(code);
}

struct ChildRun {
  Report report;
  bool killed = false;
  int signal = 0;  // the signal that ended the child, if any
  double wall_seconds = 0;
  double maxrss_mb = NAN;  // getrusage of the child: both solves and what it inherited
};

ChildRun fork_and_solve(const QuadraticProgram& qp, const SolveOptions& options, const std::string& vector_path,
                        double time_cap_seconds) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("pipe failed");
  std::cout.flush();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    ::close(fds[0]);
    run_child(fds[1], qp, options, vector_path);
  }
  ::close(fds[1]);
  ::fcntl(fds[0], F_SETFL, O_NONBLOCK);
  ChildRun run;
  std::string text;
  char buffer[4096];
  auto drain = [&] {
    ssize_t n;
    while ((n = ::read(fds[0], buffer, sizeof buffer)) > 0) text.append(buffer, static_cast<size_t>(n));
  };
  Stopwatch clock;
  int status = 0;
  struct rusage usage {};
  while (true) {
    drain();
    if (::wait4(pid, &status, WNOHANG, &usage) == pid) break;
    if (clock.seconds() > time_cap_seconds) {
      ::kill(pid, SIGKILL);
      ::wait4(pid, &status, 0, &usage);
      run.killed = true;
      break;
    }
    ::usleep(20000);
  }
  run.wall_seconds = clock.seconds();
  drain();
  ::close(fds[0]);
  if (WIFSIGNALED(status)) run.signal = WTERMSIG(status);
  run.maxrss_mb = usage.ru_maxrss / 1024.0;  // kilobytes on Linux
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    const auto space = line.find(' ');
    if (space != std::string::npos) run.report[line.substr(0, space)] = line.substr(space + 1);
  }
  return run;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

// A CSV field: six digits, empty for NaN or Inf.
std::string csv_field(double x) { return csv_number(x, 6); }

double report_number(const Report& report, const std::string& key) {
  auto it = report.find(key);
  if (it == report.end()) return NAN;
  try {
    return std::stod(it->second);
  } catch (const std::exception&) {
    return NAN;
  }
}

std::string report_text(const Report& report, const std::string& key) {
  auto it = report.find(key);
  return it == report.end() ? "" : it->second;
}

// ‖a − b‖ / max(‖a‖, ‖b‖): the measure of `contactqp compare`'s pairwise agreement.
double symmetric_difference(const VectorXd& a, const VectorXd& b) {
  if (a.size() != b.size()) return NAN;
  const double scale = std::max(a.norm(), b.norm());
  return scale > 0 ? (a - b).norm() / scale : 0.0;
}

struct Arguments {
  std::string out = std::string(CONTACTQP_SOURCE_DIR) + "/benchmarks/scaling/results";
  std::string levels = "all";
  std::string scenes;    // scene files separated by commas: run these instead of the levels
  std::string backends;  // empty: every available backend
  double time_cap_seconds = 300;
  double tol = 1e-8;
};

int run(const Arguments& arguments) {
  require(arguments.time_cap_seconds > 0, "--time-cap", arguments.time_cap_seconds, "must be positive");
  require(arguments.tol > 0 && arguments.tol < 1, "--tol", arguments.tol, "must lie in (0, 1)");
  // What to solve: the Hertz levels, or the given scene files (named by their path).
  struct Case {
    std::string name, text, source;
  };
  std::vector<Case> cases;
  if (arguments.scenes.empty()) {
    for (int k : parse_levels(arguments.levels, "--levels"))
      cases.push_back({std::to_string(k), hertz_scene_text(hertz_levels()[k]),
                       arguments.out + "/scenes/hertz-level-" + std::to_string(k) + ".json"});
  } else {
    std::istringstream paths(arguments.scenes);
    std::string path;
    while (std::getline(paths, path, ',')) {
      std::ifstream file(path);
      if (!file) throw InputError("--scenes", "= " + path + ": cannot be read");
      std::ostringstream text;
      text << file.rdbuf();
      cases.push_back({path, text.str(), ""});
    }
  }
  std::vector<Backend> backends;
  if (arguments.backends.empty()) {
    backends = available_backends();
  } else {
    std::istringstream names(arguments.backends);
    std::string name;
    while (std::getline(names, name, ',')) backends.push_back(parse_backend(name, "--backends"));
  }
  make_directory(arguments.out);
  make_directory(arguments.out + "/scenes");

  std::ostringstream extra;
  extra.precision(10);
  std::string backend_list;
  for (Backend backend : backends) backend_list += (backend_list.empty() ? "\"" : ", \"") + to_string(backend) + "\"";
  extra << "{\"benchmark\": \"scaling\", \"tol\": " << arguments.tol
        << ", \"time_cap_seconds\": " << arguments.time_cap_seconds << ", \"levels\": \"" << arguments.levels
        << "\", \"scenes\": \"" << arguments.scenes << "\", \"backends\": [" << backend_list
        << "], \"peak_memory\": \"VmHWM of the forked child, reset before each solve; includes the QP it was given\"}";
  write_file_atomically(arguments.out + "/context.json", context_json("scaling", extra.str()));

  const std::string csv_path = arguments.out + "/scaling.csv";
  std::string csv = std::string(kHeader) + "\n";
  std::map<Backend, std::string> skip_reason;  // backends that hit the cap, and where

  for (const Case& item : cases) {
    if (!item.source.empty()) write_file_atomically(item.source, item.text);
    const std::string& k = item.name;
    Scene scene = parse_scene(item.text, item.source.empty() ? item.name : item.source);
    scene.solver.tol = arguments.tol;
    scene.solver.max_iterations = 100000;
    QuadraticProgram qp;
    double mesh_seconds = 0, assemble_seconds = 0;
    {
      Model model = build_model(scene);
      qp = assemble_qp(model);
      mesh_seconds = model.timings.get("mesh");
      assemble_seconds = model.timings.get("assemble");
    }
    ::malloc_trim(0);  // the mesher's freed memory goes back before the children inherit the heap
    std::cout << (item.source.empty() ? "" : "level ") << k << ": " << qp.n_dofs() << " DOFs, " << qp.n_constraints()
              << " candidates, mesh " << csv_field(mesh_seconds) << " s\n";

    struct Row {
      Backend backend;
      ChildRun run;
      std::string status, reason;
      std::string vector_path;
    };
    std::vector<Row> rows;
    for (Backend backend : backends) {
      Row row{backend, {}, "", "", ""};
      auto skipped = skip_reason.find(backend);
      if (skipped != skip_reason.end()) {
        row.status = "skipped";
        row.reason = skipped->second;
      } else {
        SolveOptions options = scene.solver;
        options.backend = backend;
        row.vector_path = arguments.out + "/.vectors-" + to_string(backend) + ".bin";
        row.run = fork_and_solve(qp, options, row.vector_path, arguments.time_cap_seconds);
        if (row.run.killed) {
          row.status = "time_cap";
          row.reason = "killed after the cap of " + csv_field(arguments.time_cap_seconds) + " s";
          skip_reason[backend] = "exceeded the cap of " + csv_field(arguments.time_cap_seconds) + " s at " +
                                 std::to_string(qp.n_dofs()) + " DOFs";
        } else if (row.run.signal) {
          row.status = "crashed";
          row.reason =
              "signal " + std::to_string(row.run.signal) + (row.run.signal == SIGKILL ? " (out of memory?)" : "");
        } else {
          row.status = report_text(row.run.report, "status");
          row.reason = report_text(row.run.report, "message");
          if (row.status.empty()) row.status = "error";
        }
      }
      std::cout << "  " << to_string(backend) << ": " << row.status << ", "
                << csv_field(report_number(row.run.report, "phase:total")) << " s (linear "
                << csv_field(report_number(row.run.report, "linear_total_seconds")) << " s), iterations "
                << report_text(row.run.report, "iterations") << ", peak "
                << csv_field(report_number(row.run.report, "peak_rss_mb")) << " MiB\n";
      rows.push_back(row);
    }

    // Agreement with active_set's solution on the same mesh, measured as `contactqp compare` does.
    VectorXd reference_u, reference_lambda;
    bool have_reference = false;
    for (const Row& row : rows)
      if (row.backend == Backend::ActiveSet && row.status == "converged")
        have_reference = read_vectors(row.vector_path, reference_u, reference_lambda);

    for (const Row& row : rows) {
      const Report& r = row.run.report;
      double diff_u = NAN, diff_lambda = NAN;
      VectorXd u, lambda;
      if (have_reference && row.backend != Backend::ActiveSet && row.status == "converged" &&
          read_vectors(row.vector_path, u, lambda)) {
        diff_u = symmetric_difference(u, reference_u);
        diff_lambda = symmetric_difference(lambda, reference_lambda);
      }
      const double total = report_number(r, "phase:total");
      const double linear_total = report_number(r, "linear_total_seconds");
      std::ostringstream line;
      line << csv_field(k) << ',' << qp.n_dofs() << ',' << qp.n_constraints() << ',' << csv_field(mesh_seconds) << ','
           << csv_field(assemble_seconds) << ',' << to_string(row.backend) << ',' << row.status << ','
           << report_text(r, "iterations") << ',' << csv_field(report_number(r, "phase:factorize")) << ','
           << csv_field(report_number(r, "phase:condense")) << ',' << csv_field(report_number(r, "phase:iterate"))
           << ',' << csv_field(report_number(r, "phase:recover")) << ',' << csv_field(report_number(r, "phase:solve"))
           << ',' << csv_field(total) << ',' << csv_field(report_number(r, "linear_factorize_seconds")) << ','
           << csv_field(report_number(r, "linear_solve_seconds")) << ',' << csv_field(linear_total) << ','
           << csv_field(total / linear_total) << ',' << csv_field(report_number(r, "peak_rss_mb")) << ','
           << csv_field(report_number(r, "linear_peak_rss_mb")) << ',' << csv_field(report_number(r, "baseline_rss_mb"))
           << ',' << csv_field(row.run.maxrss_mb) << ',' << csv_field(report_number(r, "kkt_max")) << ','
           << csv_field(report_number(r, "relative_gap")) << ',' << csv_field(diff_u) << ',' << csv_field(diff_lambda)
           << ',' << report_text(r, "ordering") << ',' << report_text(r, "factor_nonzeros") << ','
           << csv_field(report_text(r, "phases")) << ',' << csv_field(row.reason) << '\n';
      csv += line.str();
      if (!row.vector_path.empty()) std::remove(row.vector_path.c_str());
    }
    write_file_atomically(csv_path, csv);  // after every level: a long run keeps what it measured
  }
  std::cout << "wrote " << csv_path << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Scaling benchmark: every backend on Hertz meshes from 1e3 to 1e6 DOFs, against one linear solve"};
  Arguments arguments;
  app.add_option("--out", arguments.out, "Directory for scaling.csv, context.json and the generated scenes");
  app.add_option("--levels", arguments.levels, "Mesh levels: all, or numbers 0-8 separated by commas");
  app.add_option("--scenes", arguments.scenes, "Scene files separated by commas, solved instead of the levels");
  app.add_option("--backends", arguments.backends, "Backends separated by commas (default: every available one)");
  app.add_option("--time-cap", arguments.time_cap_seconds, "Seconds before a solve is killed and its backend skipped");
  app.add_option("--tol", arguments.tol, "Tolerance of every backend (default 1e-8)");
  CLI11_PARSE(app, argc, argv);
  try {
    return run(arguments);
  } catch (const InputError& error) {
    std::cerr << "scaling_benchmark: error: " << error.what() << "\n";
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "scaling_benchmark: error: " << error.what() << "\n";
    return 1;
  }
}
