// The LCP solver of the active-set backend (solvers/lcp.hpp) on small dense problems whose
// solutions are known: by hand, by enumerating the active sets of the QP the LCP is the dual
// of, degenerate and singular ones, and one on which plain active-set steps cycle.
#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "lcp.hpp"
#include "qp/dense_decompositions.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::detail;
using namespace contactqp::testing;

namespace {

// The dual of min ½uᵀKu − fᵀu s.t. Bu ≤ g: S = B K⁻¹ Bᵀ, h = B K⁻¹ f − g.
struct DualLcp {
  Eigen::MatrixXd S;
  Eigen::VectorXd h;
};

DualLcp dual_of(const QuadraticProgram& qp) {
  const Eigen::MatrixXd K(qp.K), B(qp.B);
  const Eigen::LLT<Eigen::MatrixXd> llt(K);
  return {B * llt.solve(B.transpose()), B * llt.solve(qp.f) - qp.g};
}

// max(‖min(λ, w)‖∞, ‖max(0, −λ)‖∞, ‖max(0, −w)‖∞) with w = Sλ − h: zero at a solution.
double lcp_error(const Eigen::MatrixXd& S, const Eigen::VectorXd& h, const Eigen::VectorXd& lambda) {
  const Eigen::VectorXd w = S * lambda - h;
  return std::max(
      {lambda.cwiseMin(w).cwiseAbs().maxCoeff(), (-lambda).cwiseMax(0.0).maxCoeff(), (-w).cwiseMax(0.0).maxCoeff()});
}

LcpOptions tight() {
  LcpOptions options;
  options.tol = 1e-13;
  return options;
}

}  // namespace

TEST_CASE("the LCP solver solves a 2 × 2 problem by hand", "[unit][lcp]") {
  // S = [2 1; 1 2], h = (1, −1): with λ₂ = 0, 2λ₁ = 1, and w₂ = λ₁ + 1 = 1.5 > 0.
  Eigen::MatrixXd S(2, 2);
  S << 2, 1, 1, 2;
  const Eigen::VectorXd h = Eigen::Vector2d(1, -1);
  const LcpResult r = solve_lcp(DenseLcpOperator(S), h, tight());
  REQUIRE(r.outcome == LcpOutcome::Converged);
  CHECK(r.lambda[0] == Approx(0.5).margin(1e-15));
  CHECK(r.lambda[1] == 0.0);
  CHECK(r.w[1] == Approx(1.5));
  CHECK(r.iterations == 1);
  CHECK(r.active == 1);
}

TEST_CASE("the LCP solver returns λ = 0 without a step when nothing is in contact", "[unit][lcp]") {
  const Eigen::MatrixXd S = Eigen::Matrix2d::Identity();
  const LcpResult r = solve_lcp(DenseLcpOperator(S), Eigen::Vector2d(-1, -2), tight());
  REQUIRE(r.outcome == LcpOutcome::Converged);
  CHECK(r.lambda.isZero(0));
  CHECK(r.iterations == 0);
}

TEST_CASE("the LCP solver finds the enumerated solution of random dual problems", "[unit][lcp]") {
  const unsigned seed = GENERATE(range(1u, 25u));
  const int n = 8 + static_cast<int>(seed % 5), m = 2 + static_cast<int>(seed % 7);
  CAPTURE(seed, n, m);
  const QuadraticProgram qp = random_qp(n, m, seed);
  const ExactSolution exact = solve_by_enumeration(qp);
  const DualLcp lcp = dual_of(qp);
  const LcpResult r = solve_lcp(DenseLcpOperator(lcp.S), lcp.h, tight());
  REQUIRE(r.outcome == LcpOutcome::Converged);
  CHECK((r.lambda - exact.lambda).norm() <= 1e-10 * std::max(1.0, exact.lambda.norm()));
  CHECK(lcp_error(lcp.S, lcp.h, r.lambda) <= 1e-12 * std::max(1.0, lcp.h.cwiseAbs().maxCoeff()));
  CHECK(r.iterations <= 10);
}

TEST_CASE("the matrix-free variant (CG on the active block) agrees with the dense one", "[unit][lcp]") {
  const unsigned seed = GENERATE(range(30u, 36u));
  CAPTURE(seed);
  const QuadraticProgram qp = random_qp(12, 9, seed);
  const DualLcp lcp = dual_of(qp);
  const LcpResult dense = solve_lcp(DenseLcpOperator(lcp.S), lcp.h, tight());
  const MatrixFreeLcpOperator matrix_free(
      9, [&](const Eigen::VectorXd& x) { return Eigen::VectorXd(lcp.S * x); }, 1e-14);
  LcpOptions options = tight();
  options.tol = 1e-11;
  const LcpResult iterative = solve_lcp(matrix_free, lcp.h, options);
  REQUIRE(dense.outcome == LcpOutcome::Converged);
  REQUIRE(iterative.outcome == LcpOutcome::Converged);
  CHECK((iterative.lambda - dense.lambda).norm() <= 1e-9 * std::max(1.0, dense.lambda.norm()));
  CHECK(matrix_free.products() > 0);
}

TEST_CASE("a degenerate row (λ = 0 and w = 0 at the solution) does not upset the solver", "[unit][lcp]") {
  // Built backwards from λ* = (1, 0, 2), w* = (0, 0, 0): row 2 is active with zero force.
  Eigen::MatrixXd S(3, 3);
  S << 4, 1, 0.5, 1, 3, 1, 0.5, 1, 2;
  const Eigen::Vector3d lambda_exact(1, 0, 2);
  const Eigen::VectorXd h = S * lambda_exact;
  const LcpResult r = solve_lcp(DenseLcpOperator(S), h, tight());
  REQUIRE(r.outcome == LcpOutcome::Converged);
  CHECK((r.lambda - lambda_exact).norm() <= 1e-13);
  CHECK(r.w.cwiseAbs().maxCoeff() <= 1e-13);
}

TEST_CASE("a singular or nearly singular S (a duplicated row) still gives a solution", "[unit][lcp]") {
  // Rows 1 and 2 are the same constraint: only λ₁ + λ₂ is determined.
  const double perturbation = GENERATE(0.0, 1e-13, 1e-9);
  CAPTURE(perturbation);
  Eigen::MatrixXd S(3, 3);
  S << 2, 1, 1, 1, 1, 1, 1, 1, 1;
  S(2, 2) += perturbation;
  const Eigen::Vector3d h(1, 1, 1);  // λ = (0, t, 1 − t) for any t ∈ [0, 1] when S is singular
  const LcpResult r = solve_lcp(DenseLcpOperator(S), h, tight());
  REQUIRE(r.outcome == LcpOutcome::Converged);
  CHECK(lcp_error(S, h, r.lambda) <= 1e-12);
  CHECK(r.lambda[1] + r.lambda[2] == Approx(1.0).epsilon(1e-8));
  CHECK(r.lambda[0] == Approx(0.0).margin(1e-8));
}

TEST_CASE("plain active-set steps cycle on a 3 × 3 SPD problem, and the safeguard ends it", "[unit][lcp]") {
  // Found by a random search (3 × 3 SPD, start λ = 0): the active sets go {2} → {0,1,2} → {0}
  // → {2} → ... forever, while the solution has the active set {0, 2}.
  Eigen::MatrixXd S(3, 3);
  S << 3.228, 3.798, -1.929, 3.798, 4.708, -2.657, -1.929, -2.657, 2.256;
  const Eigen::Vector3d h(-0.196, -0.699, 0.716);
  REQUIRE(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S).eigenvalues().minCoeff() > 0.04);

  // The solution by enumerating the 8 active sets.
  Eigen::VectorXd exact;
  for (unsigned mask = 0; mask < 8; ++mask) {
    std::vector<int> active;
    for (int i = 0; i < 3; ++i)
      if (mask & (1u << i)) active.push_back(i);
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(3);
    const Eigen::MatrixXd block = S(active, active);
    if (!active.empty()) {
      const Eigen::VectorXd solution = block.llt().solve(Eigen::VectorXd(h(active)));
      lambda(active) = solution;
    }
    if (lcp_error(S, h, lambda) < 1e-12) exact = lambda;
  }
  REQUIRE(exact.size() == 3);
  CHECK(exact[1] == 0.0);

  LcpOptions plain = tight();
  plain.safeguard = false;
  const LcpResult cycling = solve_lcp(DenseLcpOperator(S), h, plain);
  CHECK(cycling.outcome == LcpOutcome::Cycled);
  CHECK(cycling.cycle_detected);
  CHECK(cycling.active_set_steps == 3);

  const LcpResult safe = solve_lcp(DenseLcpOperator(S), h, tight());
  REQUIRE(safe.outcome == LcpOutcome::Converged);
  CHECK(safe.cycle_detected);
  CHECK(safe.newton_steps >= 1);
  CHECK(safe.iterations <= 10);
  CHECK((safe.lambda - exact).norm() <= 1e-12);
}

TEST_CASE("the LCP solver stops at the iteration limit with a feasible λ", "[unit][lcp]") {
  const QuadraticProgram qp = random_qp(10, 8, 7);
  const DualLcp lcp = dual_of(qp);
  LcpOptions options = tight();
  options.max_iterations = 1;
  const LcpResult r = solve_lcp(DenseLcpOperator(lcp.S), lcp.h, options);
  CHECK(r.iterations == 1);
  CHECK((r.lambda.array() >= 0).all());
  CHECK((r.w - (lcp.S * r.lambda - lcp.h)).norm() <= 1e-12 * std::max(1.0, r.w.norm()));
}
