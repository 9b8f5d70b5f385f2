#include "test_support.hpp"

#include "contactqp/solve.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <stdexcept>

namespace contactqp::testing {

QuadraticProgram make_qp(const Eigen::MatrixXd& K, const Eigen::VectorXd& f, const Eigen::MatrixXd& B,
                         const Eigen::VectorXd& g) {
  QuadraticProgram qp;
  qp.K = K.sparseView();
  qp.f = f;
  qp.B = B.sparseView();
  qp.g = g;
  return qp;
}

Eigen::MatrixXd chain_of_springs(const std::vector<double>& k, double ground) {
  const int n = static_cast<int>(k.size()) + 1;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i + 1 < n; ++i) {
    K(i, i) += k[i];
    K(i + 1, i + 1) += k[i];
    K(i, i + 1) -= k[i];
    K(i + 1, i) -= k[i];
  }
  K(0, 0) += ground;
  return K;
}

QuadraticProgram spring_against_wall(double k, double F, double gap) {
  return make_qp(Eigen::MatrixXd::Constant(1, 1, k), Eigen::VectorXd::Constant(1, F),
                 Eigen::MatrixXd::Constant(1, 1, 1.0), Eigen::VectorXd::Constant(1, gap));
}

ExactSolution solve_by_enumeration(const QuadraticProgram& qp) {
  const int n = qp.n_dofs(), m = qp.n_constraints();
  if (m > 12) throw std::invalid_argument("solve_by_enumeration: m > 12");
  const Eigen::MatrixXd K(qp.K), B(qp.B);
  std::optional<ExactSolution> best;
  double best_objective = 0;
  for (unsigned mask = 0; mask < (1u << m); ++mask) {
    std::vector<int> active;
    for (int i = 0; i < m; ++i)
      if (mask & (1u << i)) active.push_back(i);
    const int a = static_cast<int>(active.size());
    // [K  B_Aᵀ; B_A 0] [u; λ_A] = [f; g_A]
    Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n + a, n + a);
    Eigen::VectorXd rhs(n + a);
    kkt.topLeftCorner(n, n) = K;
    rhs.head(n) = qp.f;
    for (int k = 0; k < a; ++k) {
      kkt.block(0, n + k, n, 1) = B.row(active[k]).transpose();
      kkt.block(n + k, 0, 1, n) = B.row(active[k]);
      rhs[n + k] = qp.g[active[k]];
    }
    Eigen::FullPivLU<Eigen::MatrixXd> lu(kkt);
    if (lu.rank() < n + a) continue;  // dependent active rows: another set covers this point
    const Eigen::VectorXd z = lu.solve(rhs);
    ExactSolution candidate{z.head(n), Eigen::VectorXd::Zero(m)};
    for (int k = 0; k < a; ++k) candidate.lambda[active[k]] = z[n + k];
    const double scale = 1e-10 * (1 + qp.g.cwiseAbs().maxCoeff() + candidate.u.cwiseAbs().maxCoeff());
    if ((B * candidate.u - qp.g).maxCoeff() > scale) continue;
    if (candidate.lambda.size() && candidate.lambda.minCoeff() < -1e-10 * (1 + candidate.lambda.cwiseAbs().maxCoeff()))
      continue;
    const double objective = 0.5 * candidate.u.dot(K * candidate.u) - qp.f.dot(candidate.u);
    if (!best || objective < best_objective) {
      best = candidate;
      best_objective = objective;
    }
  }
  if (!best) throw std::runtime_error("solve_by_enumeration: no KKT point (infeasible QP?)");
  best->lambda = best->lambda.cwiseMax(0.0);
  return *best;
}

QuadraticProgram random_qp(int n, int m, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = normal(random);
  const Eigen::MatrixXd K = A * A.transpose() + 0.5 * n * Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd f(n);
  for (int i = 0; i < n; ++i) f[i] = normal(random);
  Eigen::MatrixXd B(m, n);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < n; ++j) B(i, j) = normal(random);
    B.row(i).normalize();
  }
  // Gaps around the unconstrained optimum's B u: some rows end up active, some not.
  const Eigen::VectorXd free_optimum = K.ldlt().solve(f);
  Eigen::VectorXd g = B * free_optimum;
  for (int i = 0; i < m; ++i) g[i] += (i % 2 == 0 ? -0.5 : 0.5) * std::abs(normal(random));
  return make_qp(K, f, B, g);
}

SolveOptions options_for(Backend backend, double tol) {
  SolveOptions options;
  options.backend = backend;
  options.tol = tol;
  options.max_iterations = 100000;
  return options;
}

std::string source_path(const std::string& relative) { return std::string(CONTACTQP_SOURCE_DIR) + "/" + relative; }

std::string read_text(const std::string& path) {
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

namespace {
std::string slurp_and_remove(const std::string& path) {
  std::string text = read_text(path);
  std::remove(path.c_str());
  return text;
}
}  // namespace

CliRun run_cli(const std::string& arguments) {
  TemporaryDirectory directory;
  const std::string out = directory.path("stdout"), err = directory.path("stderr");
  const std::string command = std::string(CONTACTQP_CLI) + " " + arguments + " >" + out + " 2>" + err;
  const int raw = std::system(command.c_str());
  CliRun run;
  // A crash shows as a signal: report it as 128 + signal, like a shell, so tests can tell.
  run.exit_status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
  run.out = slurp_and_remove(out);
  run.err = slurp_and_remove(err);
  return run;
}

TemporaryDirectory::TemporaryDirectory() {
  std::string pattern = (std::filesystem::temp_directory_path() / "contactqp-test-XXXXXX").string();
  if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
  directory_ = pattern;
}

TemporaryDirectory::~TemporaryDirectory() {
  std::error_code error;
  std::filesystem::remove_all(directory_, error);
}

std::vector<std::string> directory_listing(const std::string& directory) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

const char* const kUnitSquareMsh = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
5
1 1 "bottom"
1 2 "right"
1 3 "top"
1 4 "left"
2 5 "body"
$EndPhysicalNames
$Nodes
4
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
$EndNodes
$Elements
6
1 1 2 1 1 1 2
2 1 2 2 2 2 3
3 1 2 3 3 3 4
4 1 2 4 4 4 1
5 2 2 5 1 1 2 3
6 2 2 5 1 1 3 4
$EndElements
)";

std::string patched_scene(const std::string& relative, const std::string& merge_patch) {
  nlohmann::json scene = nlohmann::json::parse(read_text(source_path(relative)));
  scene.merge_patch(nlohmann::json::parse(merge_patch));
  return scene.dump(2);
}

SceneRun solve_scene(const Scene& scene) {
  SceneRun run;
  run.model = build_model(scene);
  run.qp = assemble_qp(run.model);
  run.result = solve(run.qp, scene.solver);
  run.contact = summarize_contact(run.model, run.qp, run.result.u, run.result.lambda);
  run.reactions = reactions(run.model, run.qp, run.result.u, run.result.lambda);
  return run;
}

SceneRun solve_scene(const std::string& relative, const std::string& merge_patch) {
  return solve_scene(parse_scene(patched_scene(relative, merge_patch), source_path(relative)));
}

QuadraticProgram scene_qp(const std::string& relative, const std::string& merge_patch) {
  Model model = build_model(parse_scene(patched_scene(relative, merge_patch), source_path(relative)));
  return assemble_qp(model);
}

}  // namespace contactqp::testing
