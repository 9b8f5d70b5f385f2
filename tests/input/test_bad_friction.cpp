// Bad frictional QPs and options: InputError naming the field, before any work.
#include <catch2/catch.hpp>

#include "contactqp/errors.hpp"
#include "contactqp/solve.hpp"
#include "friction_qps.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;
using Catch::Matchers::Contains;

namespace {

QuadraticProgram tresca_qp() { return known_friction_qp(4, 2, FrictionLaw::Tresca, 7).qp; }

}  // namespace

TEST_CASE("a bad friction block names its field", "[input][friction]") {
  const SolveOptions options = options_for(Backend::ActiveSet, 1e-8);
  struct Bad {
    std::function<void(QuadraticProgram&)> spoil;
    const char* names;
  };
  const std::vector<Bad> bad = {
      {[](QuadraticProgram& qp) { qp.friction.threshold[2] = -1; }, "qp.friction.threshold[2] = -1: must be ≥ 0"},
      {[](QuadraticProgram& qp) { qp.friction.threshold[1] = std::nan(""); }, "qp.friction.threshold[1]"},
      {[](QuadraticProgram& qp) { qp.friction.threshold.resize(3); },
       "qp.friction.threshold has 3 entries, expected 4"},
      {[](QuadraticProgram& qp) { qp.friction.coefficient = Eigen::VectorXd::Constant(4, 0.3); },
       "qp.friction.coefficient"},
      {[](QuadraticProgram& qp) {
         qp.friction.law = FrictionLaw::Coulomb;
         qp.friction.threshold.resize(0);
         qp.friction.coefficient = Eigen::VectorXd::Constant(4, 0.3);
         qp.friction.coefficient[0] = -0.1;
       },
       "qp.friction.coefficient[0] = -0.1"},
      {[](QuadraticProgram& qp) { qp.friction.n_directions = 3; }, "qp.friction.n_directions = 3"},
      {[](QuadraticProgram& qp) { qp.friction.T.conservativeResize(7, qp.friction.T.cols()); },
       "qp.friction.T is 7 × "},
      {[](QuadraticProgram& qp) { qp.friction.offset.resize(2); }, "qp.friction.offset has 2 entries, expected 8"},
      {[](QuadraticProgram& qp) { qp.friction.law = FrictionLaw::None; }, "qp.friction.law = none"},
  };
  for (const Bad& b : bad) {
    QuadraticProgram qp = tresca_qp();
    b.spoil(qp);
    CAPTURE(b.names);
    CHECK_THROWS_WITH(solve(qp, options), Contains(b.names));
  }
}

TEST_CASE("friction on a backend that does not solve it is refused, naming the backends that do", "[input][friction]") {
  const QuadraticProgram qp = tresca_qp();
  for (Backend backend : available_backends()) {
    if (backend_solves(backend, qp)) continue;
    CAPTURE(to_string(backend));
    CHECK_THROWS_WITH(solve(qp, options_for(backend, 1e-8)),
                      Contains("backend = \"" + to_string(backend) + "\": does not solve") && Contains("tresca") &&
                          Contains("active_set"));
  }
}

TEST_CASE("a warm start of the wrong size names its field", "[input][friction]") {
  const QuadraticProgram qp = tresca_qp();
  for (Backend backend : available_backends(qp)) {
    CAPTURE(to_string(backend));
    SolveOptions options = options_for(backend, 1e-8);
    options.initial.lambda = Eigen::VectorXd::Zero(3);
    CHECK_THROWS_WITH(solve(qp, options), Contains("initial.lambda has 3 entries, B has 4 rows"));
    options.initial.lambda.resize(0);
    options.initial.lambda_t = Eigen::VectorXd::Zero(5);
    CHECK_THROWS_WITH(solve(qp, options), Contains("initial.lambda_t has 5 entries, expected 8"));
  }
}
