// One check, every backend: each available backend against exact solutions and against
// the others. New backends are picked up from available_backends().
#include <catch2/catch.hpp>
#include <random>
#include <thread>

#include "contactqp/certificate.hpp"
#include "contactqp/post.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

// A QP built backwards from its solution: u* and λ* are chosen, with the first rows active
// (g = B u*), half of those degenerate (λ* = 0 although active), the rest inactive; then
// f = K u* + Bᵀλ* makes (u*, λ*) its KKT point, unique because K is positive definite and
// the m ≤ n rows are independent.
struct KnownQp {
  QuadraticProgram qp;
  ExactSolution exact;
};

KnownQp degenerate_qp(int n, int m, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.5, 1.5);
  Eigen::MatrixXd A(n, n), B(m, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = normal(random);
  const Eigen::MatrixXd K = A * A.transpose() + 0.5 * n * Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < n; ++j) B(i, j) = normal(random);
    B.row(i).normalize();
  }
  Eigen::VectorXd u(n), lambda = Eigen::VectorXd::Zero(m);
  for (int j = 0; j < n; ++j) u[j] = normal(random);
  Eigen::VectorXd g = B * u;
  const int active = (2 * m) / 3;
  for (int i = 0; i < m; ++i) {
    if (i < active / 2)
      lambda[i] = uniform(random);  // active and loaded
    else if (i >= active)
      g[i] += uniform(random);  // inactive
    // else: active with λ = 0, the degenerate case
  }
  const Eigen::VectorXd f = K * u + B.transpose() * lambda;
  return {make_qp(K, f, B, g), {u, lambda}};
}

// What a converged backend owes at tol: its relative residuals below tol, so the solution
// error is tol times the conditioning of these small, well-conditioned problems.
constexpr double kAccuracyFactor = 1e4;

}  // namespace

TEST_CASE("every backend solves random QPs to their enumerated solution", "[cross_backend]") {
  const Backend backend = GENERATE(from_range(available_backends()));
  const unsigned seed = GENERATE(range(100u, 106u));
  CAPTURE(to_string(backend), seed);
  const QuadraticProgram qp = random_qp(8, 6, seed);
  const ExactSolution exact = solve_by_enumeration(qp);
  const SolveResult r = solve(qp, options_for(backend, 1e-10));
  CAPTURE(r.message);
  REQUIRE(r.status == Status::Converged);
  CHECK(relative_difference(r.u, exact.u) < 1e-6);
  CHECK((r.lambda - exact.lambda).norm() < 1e-6 * std::max(1.0, exact.lambda.norm()));
  const Certificate c = certify(qp, r.u, r.lambda);
  CHECK(c.kkt_max() < 1e-6);
  CHECK(std::abs(c.relative_gap) < 1e-6);
}

TEST_CASE("every backend reports finite numbers and an iteration count", "[cross_backend]") {
  const Backend backend = GENERATE(from_range(available_backends()));
  CAPTURE(to_string(backend));
  const SolveResult r = solve(random_qp(4, 3, 9), options_for(backend, 1e-8));
  CHECK(r.iterations > 0);
  CHECK(r.u.allFinite());
  CHECK(r.lambda.allFinite());
  CHECK((r.lambda.array() >= 0).all());
}

TEST_CASE("each backend holds a spring against a wall, λ ≥ 0 pushing back", "[cross_backend]") {
  const Backend backend = GENERATE(from_range(available_backends()));
  CAPTURE(to_string(backend));
  const double k = 3.0, F = 2.0, tol = 1e-10;
  SECTION("in contact: λ = F − k·gap") {
    const SolveResult r = solve(spring_against_wall(k, F, 0.5), options_for(backend, tol));
    CAPTURE(r.message);
    REQUIRE(r.status == Status::Converged);
    CHECK(r.u[0] == Approx(0.5).epsilon(kAccuracyFactor * tol));
    CHECK(r.lambda[0] == Approx(F - k * 0.5).epsilon(kAccuracyFactor * tol));
  }
  SECTION("short of the wall: λ = 0") {
    const SolveResult r = solve(spring_against_wall(k, F, 1.0), options_for(backend, tol));
    CAPTURE(r.message);
    REQUIRE(r.status == Status::Converged);
    CHECK(r.u[0] == Approx(F / k).epsilon(kAccuracyFactor * tol));
    CHECK(r.lambda[0] == Approx(0.0).margin(kAccuracyFactor * tol * F));
  }
}

TEST_CASE("every backend solves degenerate QPs: rows active with λ = 0", "[cross_backend]") {
  const Backend backend = GENERATE(from_range(available_backends()));
  CAPTURE(to_string(backend));
  // Without strict complementarity a point whose KKT residuals are ε lies O(√ε) from the
  // solution, not O(ε) (the Hölder error bound of monotone complementarity problems): an
  // interior point, whose λᵢ·sᵢ = μ splits between λᵢ and sᵢ, shows it; projections don't.
  const double tol = 1e-12, accuracy = 10 * std::sqrt(tol);
  SECTION("the free optimum lies exactly on the bound") {
    // min ½|u|² − u₀  s.t.  u₀ ≤ 1: the solution (1, 0) with λ = 0.
    const QuadraticProgram qp = make_qp(Eigen::MatrixXd::Identity(2, 2), Eigen::Vector2d(1, 0),
                                        Eigen::RowVector2d(1, 0), Eigen::VectorXd::Ones(1));
    const SolveResult r = solve(qp, options_for(backend, tol));
    CAPTURE(r.message);
    REQUIRE(r.status == Status::Converged);
    CHECK(r.u[0] == Approx(1.0).epsilon(accuracy));
    CHECK(r.u[1] == Approx(0.0).margin(accuracy));
    CHECK(r.lambda[0] == Approx(0.0).margin(accuracy));
  }
  SECTION("random QPs with several weakly active rows") {
    const unsigned seed = GENERATE(range(200u, 205u));
    CAPTURE(seed);
    const KnownQp known = degenerate_qp(8, 6, seed);
    // The construction and the enumeration agree on what the solution is.
    const ExactSolution enumerated = solve_by_enumeration(known.qp);
    REQUIRE(relative_difference(enumerated.u, known.exact.u) < 1e-10);
    const SolveResult r = solve(known.qp, options_for(backend, tol));
    CAPTURE(r.message);
    REQUIRE(r.status == Status::Converged);
    CHECK(relative_difference(r.u, known.exact.u) < accuracy);
    CHECK((r.lambda - known.exact.lambda).norm() < accuracy * known.exact.lambda.norm());
  }
}

TEST_CASE("every backend solves a QP without constraints", "[cross_backend]") {
  const Backend backend = GENERATE(from_range(available_backends()));
  CAPTURE(to_string(backend));
  const QuadraticProgram qp =
      make_qp(Eigen::Matrix2d{{2, 1}, {1, 3}}, Eigen::Vector2d(1, 2), Eigen::MatrixXd(0, 2), Eigen::VectorXd(0));
  const SolveResult r = solve(qp, options_for(backend, 1e-10));
  CAPTURE(r.message);
  REQUIRE(r.status == Status::Converged);
  CHECK(r.u[0] == Approx(0.2).epsilon(1e-9));
  CHECK(r.u[1] == Approx(0.6).epsilon(1e-9));
  CHECK(r.lambda.size() == 0);
}

TEST_CASE("every backend gives the same answer in other units, scaled or not", "[cross_backend]") {
  const Backend backend = GENERATE(from_range(available_backends()));
  const bool scale = GENERATE(true, false);
  CAPTURE(to_string(backend), scale);
  // K and f in units 1e9 times larger (a steel-like E), gaps in units 1e-3 times smaller:
  // u scales like the gaps, λ like K·u.
  const QuadraticProgram qp = random_qp(6, 5, 17);
  QuadraticProgram stiff = qp;
  stiff.K *= 1e9;
  stiff.f *= 1e6;
  stiff.g *= 1e-3;
  const ExactSolution exact = solve_by_enumeration(qp);
  SolveOptions options = options_for(backend, 1e-10);
  options.scale = scale;
  const SolveResult r = solve(stiff, options);
  CAPTURE(r.message);
  REQUIRE(r.status == Status::Converged);
  CHECK(relative_difference(VectorXd(r.u * 1e3), exact.u) < 1e-6);
  CHECK(relative_difference(VectorXd(r.lambda * 1e-6), exact.lambda) < 1e-6);
}

TEST_CASE("every backend leaves the QP untouched", "[cross_backend]") {
  const Backend backend = GENERATE(from_range(available_backends()));
  CAPTURE(to_string(backend));
  const QuadraticProgram qp = random_qp(5, 4, 42);
  const QuadraticProgram copy = qp;
  solve(qp, options_for(backend, 1e-8));
  CHECK((SparseMatrix(qp.K - copy.K)).norm() == 0.0);
  CHECK((qp.f - copy.f).norm() == 0.0);
  CHECK((SparseMatrix(qp.B - copy.B)).norm() == 0.0);
  CHECK((qp.g - copy.g).norm() == 0.0);
}

TEST_CASE("weak duality holds on every iterate of every backend that is feasible", "[cross_backend][certificate]") {
  const Backend backend = GENERATE(from_range(available_backends()));
  CAPTURE(to_string(backend));
  const QuadraticProgram qp = random_qp(8, 6, 11);
  const ExactSolution exact = solve_by_enumeration(qp);
  const Certificate optimum = certify(qp, exact.u, exact.lambda);
  SolveOptions options = options_for(backend, 1e-10);
  int feasible = 0, seen = 0;
  // θ(λ_k) ≤ J(u*) for every λ_k ≥ 0 (u* is feasible), and J(u_k) ≥ θ(λ_k) whenever u_k is
  // feasible: a primal method (Ipopt) mostly shows the second, a dual one the first.
  options.observer = [&](int, const Eigen::VectorXd& u, const Eigen::VectorXd& lambda) {
    ++seen;
    REQUIRE((lambda.array() >= 0).all());
    const Certificate c = certify(qp, u, lambda);
    CHECK(c.dual_objective <= optimum.objective + 1e-12 * std::abs(optimum.objective));
    if ((qp.B * u - qp.g).maxCoeff() <= 0) {
      ++feasible;
      CHECK(c.duality_gap >= -1e-12 * std::abs(c.objective));
    }
  };
  const SolveResult r = solve(qp, options);
  CAPTURE(r.message);
  REQUIRE(r.status == Status::Converged);
  CHECK(seen >= r.iterations);
  CHECK(seen > 0);
  INFO(feasible << " of " << seen << " iterates were primal feasible");
}

TEST_CASE("the backends agree on scenes/hertz.json at the compare tolerances", "[cross_backend][hertz]") {
  // The acceptance of `contactqp compare scenes/hertz.json --tol 1e-10`, in process.
  Scene scene = load_scene(source_path("scenes/hertz.json"));
  scene.solver.tol = 1e-10;
  Model model = build_model(scene);
  const QuadraticProgram qp = assemble_qp(model);
  struct Run {
    Backend backend;
    SolveResult result;
  };
  std::vector<Run> runs;
  for (Backend backend : available_backends()) {
    SolveOptions options = scene.solver;
    options.backend = backend;
    Run run{backend, solve(qp, options)};
    CAPTURE(to_string(backend), run.result.message);
    REQUIRE(run.result.status == Status::Converged);
    CHECK(run.result.iterations > 0);
    const Certificate c = certify(qp, run.result.u, run.result.lambda, run.result.K_factor.get());
    CHECK(std::abs(c.relative_gap) <= 1e-8);
    CHECK(c.kkt_max() <= 1e-9);
    runs.push_back(std::move(run));
  }
  for (size_t i = 0; i < runs.size(); ++i)
    for (size_t j = 0; j < i; ++j) {
      CAPTURE(to_string(runs[i].backend), to_string(runs[j].backend));
      CHECK(relative_difference(runs[i].result.u, runs[j].result.u) <= 1e-6);
      CHECK(relative_difference(runs[i].result.lambda, runs[j].result.lambda) <= 1e-5);
      const ContactSummary a = summarize_contact(model, qp, runs[i].result.u, runs[i].result.lambda);
      const ContactSummary b = summarize_contact(model, qp, runs[j].result.u, runs[j].result.lambda);
      CHECK(a.half_width == Approx(b.half_width).epsilon(1e-6));
      CHECK(a.max_pressure == Approx(b.max_pressure).epsilon(1e-5));
    }
}

TEST_CASE("concurrent solves in one process: Ipopt is serialised, the others are independent", "[cross_backend]") {
  const Backend backend = GENERATE(from_range(available_backends()));
  CAPTURE(to_string(backend));
  const QuadraticProgram qp = random_qp(30, 10, 5);
  const ExactSolution exact = solve_by_enumeration(qp);
  std::vector<SolveResult> results(4);
  std::vector<std::thread> threads;
  for (SolveResult& result : results)
    threads.emplace_back([&qp, &result, backend] { result = solve(qp, options_for(backend, 1e-10)); });
  for (std::thread& thread : threads) thread.join();
  for (const SolveResult& r : results) {
    CAPTURE(r.message);
    REQUIRE(r.status == Status::Converged);
    CHECK(relative_difference(r.u, exact.u) < 1e-6);
  }
}
