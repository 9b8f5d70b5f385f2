// Small QPs whose solutions are known exactly (by hand, or by enumerating every active set),
// and the certificate's numbers on them.
#include <catch2/catch.hpp>

#include "contactqp/backends/uzawa.hpp"
#include "contactqp/certificate.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

TEST_CASE("Uzawa holds a spring against a wall", "[validation][uzawa]") {
  const double k = 3.0, F = 2.0;
  SECTION("in contact") {
    const SolveResult r = solve(spring_against_wall(k, F, 0.5), options_for(Backend::Uzawa, 1e-12));
    REQUIRE(r.status == Status::Converged);
    CHECK(r.u[0] == Approx(0.5).epsilon(1e-10));
    CHECK(r.lambda[0] == Approx(F - k * 0.5).epsilon(1e-10));
  }
  SECTION("not reaching the wall: λ = 0 exactly") {
    const SolveResult r = solve(spring_against_wall(k, F, 1.0), options_for(Backend::Uzawa, 1e-12));
    REQUIRE(r.status == Status::Converged);
    CHECK(r.u[0] == Approx(F / k).epsilon(1e-14));
    CHECK(r.lambda[0] == 0.0);
  }
}

TEST_CASE("Uzawa matches the enumerated solution of random QPs", "[validation][uzawa]") {
  const unsigned seed = GENERATE(range(1u, 9u));
  const QuadraticProgram qp = random_qp(6, 5, seed);
  const ExactSolution exact = solve_by_enumeration(qp);
  const SolveResult r = solve(qp, options_for(Backend::Uzawa, 1e-12));
  CAPTURE(seed, r.iterations, r.message);
  REQUIRE(r.status == Status::Converged);
  CHECK(relative_difference(r.u, exact.u) < 1e-8);
  CHECK((r.lambda - exact.lambda).norm() < 1e-8 * std::max(1.0, exact.lambda.norm()));
}

TEST_CASE("a degenerate constraint, active with λ = 0", "[validation][uzawa]") {
  // min ½|u|² − u₀  s.t.  u₀ ≤ 1: the free optimum (1, 0) lies exactly on the bound.
  const QuadraticProgram qp = make_qp(Eigen::MatrixXd::Identity(2, 2), Eigen::Vector2d(1, 0), Eigen::RowVector2d(1, 0),
                                      Eigen::VectorXd::Ones(1));
  const SolveResult r = solve(qp, options_for(Backend::Uzawa, 1e-12));
  REQUIRE(r.status == Status::Converged);
  CHECK(r.u[0] == Approx(1.0).epsilon(1e-12));
  CHECK(r.lambda[0] == Approx(0.0).margin(1e-12));
}

TEST_CASE("no constraints: the linear solution, in one iteration", "[validation][uzawa]") {
  QuadraticProgram qp =
      make_qp(Eigen::Matrix2d{{2, 1}, {1, 3}}, Eigen::Vector2d(1, 2), Eigen::MatrixXd(0, 2), Eigen::VectorXd(0));
  const SolveResult r = solve(qp, options_for(Backend::Uzawa, 1e-10));
  REQUIRE(r.status == Status::Converged);
  CHECK(r.iterations == 1);
  CHECK(r.u[0] == Approx(0.2));
  CHECK(r.u[1] == Approx(0.6));
  CHECK(r.lambda.size() == 0);
}

TEST_CASE("solve() leaves the QP untouched, and scaling does not change the answer", "[validation][uzawa]") {
  const QuadraticProgram qp = random_qp(5, 4, 42);
  const QuadraticProgram copy = qp;
  SolveOptions options = options_for(Backend::Uzawa, 1e-12);
  const SolveResult scaled = solve(qp, options);
  CHECK((SparseMatrix(qp.K - copy.K)).norm() == 0.0);
  CHECK((qp.f - copy.f).norm() == 0.0);
  CHECK((SparseMatrix(qp.B - copy.B)).norm() == 0.0);
  CHECK((qp.g - copy.g).norm() == 0.0);
  options.scale = false;
  const SolveResult unscaled = solve(qp, options);
  CHECK(relative_difference(scaled.u, unscaled.u) < 1e-9);
  CHECK(relative_difference(scaled.lambda, unscaled.lambda) < 1e-9);
}

TEST_CASE("Uzawa's step: beyond ρ_max it diverges, far below it stops at max_iterations", "[validation][uzawa]") {
  const QuadraticProgram qp = random_qp(6, 5, 7);
  SolveOptions options = options_for(Backend::Uzawa, 1e-10);
  const auto fraction_of_max = [&options](double fraction) {
    options.set(UzawaOptions{UzawaOptions::RhoRule::FractionOfMax, fraction});
  };
  SECTION("2.2 ρ_max") {
    fraction_of_max(2.2);
    const SolveResult r = solve(qp, options);
    CHECK(r.status == Status::Diverged);
    CHECK(r.iterations <= 300);
    CHECK(r.message.find("ρ_max") != std::string::npos);
    CHECK(r.u.allFinite());
    CHECK(r.lambda.allFinite());
  }
  SECTION("1e-6 ρ_max") {
    fraction_of_max(1e-6);
    options.max_iterations = 500;
    const SolveResult r = solve(qp, options);
    CHECK(r.status == Status::MaxIterations);
    CHECK(r.iterations == 500);
    CHECK(r.u.allFinite());
  }
  SECTION("an absolute step equal to 0.5 ρ_max gives the same iterates as 0.5x") {
    fraction_of_max(0.5);
    const SolveResult relative = solve(qp, options);
    options.set(UzawaOptions{UzawaOptions::RhoRule::Absolute, 0.5 * relative.diagnostics.at("rho_max")});
    const SolveResult absolute = solve(qp, options);
    CHECK(absolute.iterations == relative.iterations);
    CHECK(relative_difference(absolute.lambda, relative.lambda) < 1e-12);
  }
}

TEST_CASE("the certificate: zero gap at the optimum, the exact gap elsewhere", "[validation][certificate]") {
  const QuadraticProgram qp = random_qp(6, 5, 3);
  const ExactSolution exact = solve_by_enumeration(qp);
  const Certificate at_optimum = certify(qp, exact.u, exact.lambda);
  CHECK(at_optimum.kkt_max() < 1e-12);
  CHECK(std::abs(at_optimum.relative_gap) < 1e-12);

  // The optimal (feasible) u with a λ ≥ 0 that is not optimal: the gap J(u) − θ(λ) from the
  // definitions, with a dense inverse, and positive by weak duality.
  const Eigen::MatrixXd K(qp.K), B(qp.B);
  const Eigen::VectorXd& u = exact.u;
  const Eigen::VectorXd lambda = exact.lambda + Eigen::VectorXd::Constant(exact.lambda.size(), 0.1);
  const Certificate c = certify(qp, u, lambda);
  const Eigen::VectorXd rhs = qp.f - B.transpose() * lambda;
  const double theta = -0.5 * rhs.dot(K.ldlt().solve(rhs)) - qp.g.dot(lambda);
  const double J = 0.5 * u.dot(K * u) - qp.f.dot(u);
  CHECK(c.objective == Approx(J).epsilon(1e-12));
  CHECK(c.dual_objective == Approx(theta).epsilon(1e-12));
  CHECK(c.duality_gap == Approx(J - theta).epsilon(1e-10));
  CHECK(c.duality_gap > 0);
  CHECK(c.stationarity > 1e-3);
}
