// One check, every backend: each available backend against exact solutions and against
// the others. New backends are picked up from available_backends().
#include <catch2/catch.hpp>

#include "contactqp/certificate.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

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
