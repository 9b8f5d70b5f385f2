// Uzawa's step ρ: the spectrum estimate of S = B K⁻¹ Bᵀ against spectra known analytically,
// the automatic step against the analytic optimum, divergence above ρ_max, the accelerated
// variant against plain Uzawa and exact solutions, and the --rho options through the CLI.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>

#include "contactqp/backends/uzawa.hpp"
#include "contactqp/cholesky.hpp"
#include "contactqp/model.hpp"
#include "contactqp/solve.hpp"
#include "qp/dense_decompositions.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

// min ½uᵀKu − fᵀu s.t. u ≤ g (B = I) with the load pushing every DOF past its bound, so the
// unconstrained solution violates every row and every row ends up active: u = g, λ = f − Kg,
// and S = K⁻¹, whose spectrum is that of K inverted.
QuadraticProgram all_active(const Eigen::MatrixXd& K) {
  const int n = static_cast<int>(K.rows());
  const Eigen::VectorXd g = Eigen::VectorXd::Constant(n, 0.1);
  const Eigen::VectorXd f = K * g + Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  return make_qp(K, f, Eigen::MatrixXd::Identity(n, n), g);
}

// Stiffnesses spread over two decades: S = diag(1/k_i), λ_min = 1/100, λ_max = 1.
Eigen::MatrixXd diagonal_K() { return Eigen::VectorXd::LinSpaced(20, 1.0, 100.0).asDiagonal(); }

// The 1D Dirichlet Laplacian tridiag(−1, 2, −1): eigenvalues 2 − 2cos(jπ/(n+1)), j = 1..n.
Eigen::MatrixXd chain_K(int n) {
  Eigen::MatrixXd K = 2 * Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i + 1 < n; ++i) K(i, i + 1) = K(i + 1, i) = -1;
  return K;
}

struct KnownSpectrum {
  const char* name;
  Eigen::MatrixXd K;
  double lambda_min, lambda_max;  // of S = K⁻¹
};

std::vector<KnownSpectrum> known_spectra() {
  const int n = 30;
  const double pi = std::acos(-1.0);
  return {{"diagonal K", diagonal_K(), 1.0 / 100.0, 1.0},
          {"chain K", chain_K(n), 1.0 / (2 + 2 * std::cos(pi / (n + 1))), 1.0 / (2 - 2 * std::cos(pi / (n + 1)))}};
}

SolveOptions rho_options(Backend backend, UzawaOptions::RhoRule rule, double rho, double tol = 1e-10) {
  SolveOptions options = options_for(backend, tol);
  options.set(UzawaOptions{rule, rho});
  return options;
}

const Backend kUzawaBackends[] = {Backend::Uzawa, Backend::UzawaAccelerated};

}  // namespace

TEST_CASE("the spectrum of S and the automatic ρ match the analytic values", "[validation][uzawa][rho]") {
  for (const KnownSpectrum& known : known_spectra()) {
    CAPTURE(known.name);
    const QuadraticProgram qp = all_active(known.K);
    const double rho_opt = 2 / (known.lambda_min + known.lambda_max);
    const double tol = 1e-12;
    const SolveResult r = solve(qp, options_for(Backend::Uzawa, tol));
    CAPTURE(r.message);
    REQUIRE(r.status == Status::Converged);
    CHECK(r.diagnostics.at("lambda_max_S") == Approx(known.lambda_max).epsilon(1e-6));
    CHECK(r.diagnostics.at("lambda_min_S") == Approx(known.lambda_min).epsilon(0.01));
    CHECK(r.diagnostics.at("rho_max") == Approx(2 / known.lambda_max).epsilon(1e-6));
    CHECK(r.diagnostics.at("rho_opt") == Approx(rho_opt).epsilon(0.05));
    CHECK(r.diagnostics.at("rho") == Approx(rho_opt).epsilon(0.05));
    CHECK(r.diagnostics.at("spectrum_rows") == qp.n_constraints());
    // u = g, λ = f − Kg exactly. The step λ_{k+1} − λ_k ≤ tol·‖λ‖ leaves an error of about
    // κ·tol/2 at the rate (κ − 1)/(κ + 1); u − u* = −S(λ − λ*) is at most λ_max times that.
    const double kappa = known.lambda_max / known.lambda_min;
    const Eigen::VectorXd lambda_exact = qp.f - qp.K * qp.g;
    CHECK(relative_difference(r.lambda, lambda_exact) < kappa * tol);
    CHECK((r.u - qp.g).norm() < known.lambda_max * kappa * tol * lambda_exact.norm());
    // At ρ_opt the error contracts by (κ − 1)/(κ + 1) per step: iterations ≈ ln(1/tol)/−ln of that.
    const double predicted = std::log(1 / tol) / -std::log((kappa - 1) / (kappa + 1));
    CHECK(r.iterations > 0.5 * predicted);
    CHECK(r.iterations < 1.5 * predicted);
  }
}

TEST_CASE("the estimate covers the rows the unconstrained solution violates", "[validation][uzawa][rho]") {
  // The chain with only every other DOF pushed past its bound: the working set is those rows,
  // and λ(S) is that of the principal block of K⁻¹ on them (dense eigenvalues as the truth).
  const int n = 12;
  const Eigen::MatrixXd K = chain_K(n);
  const Eigen::VectorXd u_free = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  Eigen::VectorXd g = u_free;
  std::vector<int> violated;
  for (int i = 0; i < n; i += 2) {
    g[i] = 0.5 * u_free[i];
    violated.push_back(i);
  }
  g += Eigen::VectorXd::Constant(n, 1e-3);  // the others keep a small clearance
  for (int i = 1; i < n; i += 2) g[i] += 2.0;
  const QuadraticProgram qp = make_qp(K, K * u_free, Eigen::MatrixXd::Identity(n, n), g);
  const Eigen::MatrixXd S = K.inverse();
  Eigen::MatrixXd block(violated.size(), violated.size());
  for (size_t i = 0; i < violated.size(); ++i)
    for (size_t j = 0; j < violated.size(); ++j) block(i, j) = S(violated[i], violated[j]);
  const Eigen::VectorXd exact = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(block).eigenvalues();

  const SolveResult r = solve(qp, options_for(Backend::Uzawa, 1e-10));
  REQUIRE(r.status == Status::Converged);
  CHECK(r.diagnostics.at("spectrum_rows") == static_cast<double>(violated.size()));
  CHECK(r.diagnostics.at("spectrum_all_rows") == 0);
  CHECK(r.diagnostics.at("lambda_max_S") == Approx(exact.maxCoeff()).epsilon(1e-8));
  CHECK(r.diagnostics.at("lambda_min_S") == Approx(exact.minCoeff()).epsilon(1e-8));
  const ExactSolution truth = solve_by_enumeration(qp);
  CHECK(relative_difference(r.u, truth.u) < 1e-8);
}

TEST_CASE("ρ in the caller's units: E × 1e6 scales ρ and ρ_max, not ρ/ρ_max or the iterations",
          "[validation][uzawa][rho]") {
  const QuadraticProgram qp = all_active(chain_K(10));
  QuadraticProgram stiff = qp;
  stiff.K *= 1e6;
  stiff.f *= 1e6;
  const SolveResult a = solve(qp, options_for(Backend::Uzawa, 1e-10));
  const SolveResult b = solve(stiff, options_for(Backend::Uzawa, 1e-10));
  CHECK(b.diagnostics.at("rho") == Approx(1e6 * a.diagnostics.at("rho")).epsilon(1e-9));
  CHECK(b.diagnostics.at("rho_max") == Approx(1e6 * a.diagnostics.at("rho_max")).epsilon(1e-9));
  CHECK(b.diagnostics.at("lambda_max_S") == Approx(1e-6 * a.diagnostics.at("lambda_max_S")).epsilon(1e-9));
  CHECK(b.iterations == a.iterations);
}

TEST_CASE("above ρ_max both variants report diverged within 300 iterations, finitely", "[validation][uzawa][rho]") {
  const Backend backend = GENERATE(from_range(std::begin(kUzawaBackends), std::end(kUzawaBackends)));
  CAPTURE(to_string(backend));
  for (const KnownSpectrum& known : known_spectra()) {
    CAPTURE(known.name);
    const QuadraticProgram qp = all_active(known.K);
    // ρ = 2.2/λ_max = 1.1 ρ_max in absolute units, and 2.2 ρ_max as a fraction.
    const std::pair<SolveOptions, double> cases[] = {
        {rho_options(backend, UzawaOptions::RhoRule::Absolute, 2.2 / known.lambda_max), 1.1},
        {rho_options(backend, UzawaOptions::RhoRule::FractionOfMax, 2.2), 2.2}};
    for (const auto& [options, fraction] : cases) {
      CAPTURE(fraction);
      const SolveResult r = solve(qp, options);
      CAPTURE(r.message);
      CHECK(r.status == Status::Diverged);
      CHECK(r.iterations <= 300);
      CHECK(r.message.find("ρ_max") != std::string::npos);
      CHECK(r.diagnostics.at("rho") / r.diagnostics.at("rho_max") == Approx(fraction).epsilon(1e-6));
      CHECK(r.u.allFinite());
      CHECK(r.lambda.allFinite());
      for (const auto& [name, value] : r.diagnostics) {
        CAPTURE(name);
        CHECK(std::isfinite(value));
      }
    }
  }
}

TEST_CASE("far below ρ_max: max_iterations, with the accuracy reached", "[validation][uzawa][rho]") {
  const Backend backend = GENERATE(from_range(std::begin(kUzawaBackends), std::end(kUzawaBackends)));
  CAPTURE(to_string(backend));
  SolveOptions options = rho_options(backend, UzawaOptions::RhoRule::FractionOfMax, 1e-6);
  options.max_iterations = 400;
  const SolveResult r = solve(all_active(chain_K(30)), options);
  CAPTURE(r.message);
  CHECK(r.status == Status::MaxIterations);
  CHECK(r.iterations == 400);
  CHECK(r.message.find("relative residual") != std::string::npos);
  REQUIRE(r.diagnostics.count("residual"));
  CHECK(r.diagnostics.at("residual") > options.tol);
  CHECK(std::isfinite(r.diagnostics.at("residual")));
  CHECK(r.u.allFinite());
  CHECK(r.lambda.allFinite());
}

TEST_CASE("the accelerated variant reaches the plain and the enumerated solution", "[validation][uzawa][rho]") {
  const unsigned seed = GENERATE(range(20u, 28u));
  CAPTURE(seed);
  const QuadraticProgram qp = random_qp(10, 8, seed);
  const ExactSolution exact = solve_by_enumeration(qp);
  const SolveResult plain = solve(qp, options_for(Backend::Uzawa, 1e-12));
  const SolveResult accelerated = solve(qp, options_for(Backend::UzawaAccelerated, 1e-12));
  CAPTURE(plain.message, accelerated.message);
  REQUIRE(plain.status == Status::Converged);
  REQUIRE(accelerated.status == Status::Converged);
  CHECK(relative_difference(accelerated.u, exact.u) < 1e-9);
  CHECK(relative_difference(accelerated.u, plain.u) < 1e-9);
  CHECK((accelerated.lambda - exact.lambda).norm() < 1e-8 * std::max(1.0, exact.lambda.norm()));
  CHECK((accelerated.lambda.array() >= 0).all());
}

TEST_CASE("the accelerated variant: fewer iterations at the same answer, every iterate observed",
          "[validation][uzawa][rho]") {
  const KnownSpectrum known = known_spectra()[1];
  const QuadraticProgram qp = all_active(known.K);
  const SolveResult plain = solve(qp, options_for(Backend::Uzawa, 1e-10));
  SolveOptions options = options_for(Backend::UzawaAccelerated, 1e-10);
  int observed = 0;
  bool dual_feasible = true;
  options.observer = [&](int k, const Eigen::VectorXd&, const Eigen::VectorXd& lambda) {
    observed = k;
    dual_feasible = dual_feasible && (lambda.array() >= 0).all();
  };
  const SolveResult accelerated = solve(qp, options);
  REQUIRE(accelerated.status == Status::Converged);
  CHECK(observed == accelerated.iterations);
  CHECK(dual_feasible);
  CHECK(accelerated.diagnostics.at("rho") == Approx(1 / known.lambda_max).epsilon(1e-6));
  CHECK(accelerated.iterations * 4 <= plain.iterations);
  CHECK(relative_difference(accelerated.u, qp.g) < 1e-8);
  CHECK(relative_difference(accelerated.lambda, qp.f - qp.K * qp.g) < 1e-8);
}

TEST_CASE("the automatic ρ falls back to every row when the working-set step does not converge",
          "[validation][uzawa][rho]") {
  // Three DOFs, u ≤ g, with S = K⁻¹ = [[1, 0, −½], [0, 0.1, 0], [−½, 0, 1]] (eigenvalues 1.5,
  // 0.5, 0.1). The unconstrained solution (2, 1, 0) violates rows 0 and 1 only, whose block
  // diag(1, 0.1) gives ρ_opt = 2/1.1; holding u₀ at its bound drives u₂ past its own, so row 2
  // ends up active too, and on the active block that step expands the error along the
  // eigenvalue 1.5 (|1 − 1.5·2/1.1| > 1). The step from every row, 2/1.6, converges.
  const Eigen::Matrix3d S{{1, 0, -0.5}, {0, 0.1, 0}, {-0.5, 0, 1}};
  const Eigen::Matrix3d K = S.inverse();
  const QuadraticProgram qp =
      make_qp(K, K * Eigen::Vector3d(2, 1, 0), Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, 0.5, 0.2));
  const ExactSolution exact = solve_by_enumeration(qp);
  REQUIRE(exact.lambda.minCoeff() > 0);
  SECTION("plain Uzawa falls back") {
    const SolveResult r = solve(qp, options_for(Backend::Uzawa, 1e-10));
    CAPTURE(r.message);
    REQUIRE(r.status == Status::Converged);
    CHECK(r.diagnostics.at("rho_fallback") == 1);
    CHECK(r.diagnostics.at("spectrum_all_rows") == 1);
    CHECK(r.diagnostics.at("lambda_max_S") == Approx(1.5).epsilon(1e-8));
    CHECK(r.diagnostics.at("rho") == Approx(2 / 1.6).epsilon(1e-6));
    CHECK(r.message.find("re-chosen from every row") != std::string::npos);
    CHECK(relative_difference(r.u, exact.u) < 1e-8);
    CHECK(relative_difference(r.lambda, exact.lambda) < 1e-8);
  }
  SECTION("the accelerated variant converges to the same solution") {
    const SolveResult r = solve(qp, options_for(Backend::UzawaAccelerated, 1e-10));
    CAPTURE(r.message);
    REQUIRE(r.status == Status::Converged);
    CHECK(relative_difference(r.u, exact.u) < 1e-8);
    CHECK(relative_difference(r.lambda, exact.lambda) < 1e-8);
  }
  SECTION("a user's step is the user's: the same step as a fraction of ρ_max diverges") {
    const SolveResult r = solve(qp, rho_options(Backend::Uzawa, UzawaOptions::RhoRule::Absolute, 2 / 1.1));
    CHECK(r.status == Status::Diverged);
    CHECK(r.diagnostics.at("rho_fallback") == 0);
  }
}

namespace {

// The Hertz QP of a scene, with its factor, for sweeps that re-solve it many times.
struct HertzQp {
  QuadraticProgram qp;
  std::shared_ptr<const LinearSolver> factor;
};

HertzQp hertz_qp(const std::string& patch) {
  Model model = build_model(parse_scene(patched_scene("scenes/hertz.json", patch)));
  HertzQp out{assemble_qp(model), nullptr};
  out.factor = solve(out.qp, options_for(Backend::Uzawa, 1e-2)).K_factor;
  return out;
}

SolveResult solve_with(const HertzQp& hertz, Backend backend, double tol, std::optional<double> fraction = {}) {
  SolveOptions options = options_for(backend, tol);
  options.max_iterations = 20000;
  options.K_factor = hertz.factor;
  if (fraction) {
    options.set(UzawaOptions{UzawaOptions::RhoRule::FractionOfMax, *fraction});
  }
  return solve(hertz.qp, options);
}

}  // namespace

TEST_CASE("Hertz: --rho auto within 25% of the best fixed ρ, the accelerated variant under 1/4",
          "[validation][uzawa][rho][hertz]") {
  const std::string patch = GENERATE(std::string(R"({"body": {"mesh": {"size": 0.2, "contact_size": 0.004}}})"),
                                     std::string(R"({"material": {"nu": 0.45}, "load": {"value": [null, -0.006]},
                                                     "body": {"mesh": {"size": 0.15, "contact_size": 0.003}}})"));
  CAPTURE(patch);
  const HertzQp hertz = hertz_qp(patch);
  const SolveResult automatic = solve_with(hertz, Backend::Uzawa, 1e-8);
  REQUIRE(automatic.status == Status::Converged);
  int best = automatic.iterations;
  double best_fraction = 0;
  for (double fraction = 0.5; fraction < 2.5; fraction *= 1.08) {
    const SolveResult r = solve_with(hertz, Backend::Uzawa, 1e-8, fraction);
    if (r.status == Status::Converged && r.iterations < best) {
      best = r.iterations;
      best_fraction = fraction;
    }
  }
  CAPTURE(automatic.iterations, best, best_fraction);
  CHECK(automatic.iterations <= 1.25 * best);

  const SolveResult accelerated = solve_with(hertz, Backend::UzawaAccelerated, 1e-8);
  CAPTURE(accelerated.iterations);
  REQUIRE(accelerated.status == Status::Converged);
  CHECK(4 * accelerated.iterations <= automatic.iterations);
  CHECK(relative_difference(accelerated.u, automatic.u) < 1e-6);
}

TEST_CASE("scenes/hertz.json: uzawa_accel needs at most 1/4 of Uzawa's iterations, same u to 1e-6",
          "[validation][uzawa][rho][hertz]") {
  const HertzQp hertz = hertz_qp("{}");
  const SolveResult plain = solve_with(hertz, Backend::Uzawa, 1e-8);
  const SolveResult accelerated = solve_with(hertz, Backend::UzawaAccelerated, 1e-8);
  CAPTURE(plain.iterations, accelerated.iterations);
  REQUIRE(plain.status == Status::Converged);
  REQUIRE(accelerated.status == Status::Converged);
  CHECK(4 * accelerated.iterations <= plain.iterations);
  CHECK(relative_difference(accelerated.u, plain.u) < 1e-6);
}

namespace {

// Every number of a JSON document, with its path; nulls and non-numbers where numbers belong
// are the caller's to judge.
void collect(const nlohmann::json& value, const std::string& path, std::vector<std::string>& nulls) {
  if (value.is_null()) nulls.push_back(path);
  if (value.is_object())
    for (auto it = value.begin(); it != value.end(); ++it) collect(it.value(), path + "." + it.key(), nulls);
  if (value.is_array())
    for (size_t i = 0; i < value.size(); ++i) collect(value[i], path + "[" + std::to_string(i) + "]", nulls);
}

}  // namespace

TEST_CASE("CLI: --rho 2.2x diverges and --rho 1e-6x stops at max_iterations, with only finite numbers",
          "[validation][uzawa][rho][cli]") {
  const std::string backend = GENERATE(std::string("uzawa"), std::string("uzawa_accel"));
  const std::string rho = GENERATE(std::string("2.2x"), std::string("1e-6x"));
  CAPTURE(backend, rho);
  TemporaryDirectory directory;
  const std::string scene = directory.path("small.json"), out = directory.path("out.json");
  {
    std::ofstream file(scene);
    file << patched_scene("scenes/hertz.json", R"({"body": {"mesh": {"size": 0.2, "contact_size": 0.004}}})");
  }
  const CliRun run =
      run_cli("solve " + scene + " --backend " + backend + " --rho " + rho + " --max-iterations 400 --json " + out);
  CAPTURE(run.out, run.err);
  CHECK(run.exit_status == 1);
  const std::string text = read_text(out);
  CHECK_FALSE(std::regex_search(text, std::regex(R"(\b(nan|inf|infinity)\b)", std::regex::icase)));
  const nlohmann::json result = nlohmann::json::parse(text);
  const std::string message = result.at("message");
  if (rho == "2.2x") {
    CHECK(result.at("status") == "diverged");
    CHECK(result.at("iterations").get<int>() <= 300);
    CHECK(message.find("ρ_max") != std::string::npos);
    CHECK(result.at("rho").get<double>() / result.at("rho_max").get<double>() == Approx(2.2));
  } else {
    CHECK(result.at("status") == "max_iterations");
    CHECK(result.at("iterations").get<int>() == 400);
    CHECK(message.find("relative residual") != std::string::npos);
    CHECK(result.at("solver").at("residual").get<double>() > 1e-8);
  }
  CHECK(result.at("rho_opt").is_number());
  std::vector<std::string> nulls;
  collect(result, "", nulls);
  CAPTURE(nulls);
  CHECK(nulls.empty());
}

TEST_CASE("CLI: --rho auto reports ρ, ρ_max, ρ_opt and the rows the spectrum covers", "[validation][uzawa][rho][cli]") {
  TemporaryDirectory directory;
  const std::string scene = directory.path("small.json"), out = directory.path("out.json");
  {
    std::ofstream file(scene);
    file << patched_scene("scenes/hertz.json", R"({"body": {"mesh": {"size": 0.2, "contact_size": 0.004}}})");
  }
  const CliRun run = run_cli("solve " + scene + " --rho auto --json " + out);
  CAPTURE(run.out, run.err);
  CHECK(run.exit_status == 0);
  const nlohmann::json result = nlohmann::json::parse(read_text(out));
  CHECK(result.at("status") == "converged");
  const double rho = result.at("rho"), rho_max = result.at("rho_max"), rho_opt = result.at("rho_opt");
  CHECK(rho == rho_opt);
  CHECK(rho_opt < rho_max);
  const nlohmann::json& spectrum = result.at("spectrum_of_S");
  CHECK(rho_max == Approx(2 / spectrum.at("lambda_max").get<double>()));
  CHECK(rho_opt == Approx(2 / (spectrum.at("lambda_max").get<double>() + spectrum.at("lambda_min").get<double>())));
  CHECK(spectrum.at("rows").get<int>() < result.at("constraints").get<int>());
  CHECK(spectrum.at("row_set").get<std::string>().find("unconstrained") != std::string::npos);
  CHECK(spectrum.at("solves").get<int>() > 0);
}
