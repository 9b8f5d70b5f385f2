// A backend added in one file: this one. It registers a toy backend for the length of each test
// (ScopedBackendRegistration, so that the tests iterating over available_backends() never see
// it), and runs it through solve(), compare_scene() and certify() as any built-in backend.
//
// The toy is projected Gauss–Seidel on the dual, for problems with a few contact rows:
//
//   S = B K⁻¹ Bᵀ, h = B K⁻¹ f − g          (dense; B u(λ) − g = h − S λ)
//   λ_i ← max(0, λ_i + (h − S λ)_i / S_ii)   (one sweep over the rows, until nothing moves)
//   u = K⁻¹ (f − Bᵀ λ)
//
// It says Converged only when certify() agrees.
#include <catch2/catch.hpp>

#include "contactqp/backend.hpp"
#include "contactqp/certificate.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/run.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

SolveResult solve_toy(const QuadraticProgram& qp, const SolveOptions& options) {
  SolveResult result;
  LinearSolverOptions settings;
  settings.tol = options.tol;
  const std::shared_ptr<const LinearSolver> K = make_linear_solver(qp.K, settings);
  result.K_factor = K;
  const Condensation condensed = K->condense(qp.B, qp.f);
  const Eigen::MatrixXd& S = condensed.S;
  const VectorXd h = condensed.c - qp.g;
  VectorXd lambda = VectorXd::Zero(qp.n_constraints());
  int max_sweeps = options.max_iterations;  // its one backend option lowers it
  const auto given = options.backend_options.find("max_sweeps");
  if (given != options.backend_options.end()) max_sweeps = std::min(max_sweeps, std::stoi(given->second));
  for (; result.iterations < max_sweeps; ++result.iterations) {
    double moved = 0;
    for (int i = 0; i < lambda.size(); ++i) {
      const double next = std::max(0.0, lambda[i] + (h[i] - S.row(i).dot(lambda)) / S(i, i));
      moved = std::max(moved, std::abs(next - lambda[i]));
      lambda[i] = next;
    }
    if (moved <= 1e-3 * options.tol * std::max(1.0, lambda.cwiseAbs().maxCoeff())) break;
  }
  result.lambda = lambda;
  result.u = K->solve(VectorXd(qp.f - qp.B.transpose() * lambda));
  const Certificate certificate = certify(qp, result.u, result.lambda, K.get());
  result.status = certificate.kkt_max() <= options.tol ? Status::Converged : Status::MaxIterations;
  result.message = "projected Gauss-Seidel on the dual: " + std::to_string(result.iterations) + " sweeps";
  return result;
}

BackendRegistration toy_backend() {
  BackendRegistration toy;
  toy.name = "toy";
  toy.summary = "projected Gauss-Seidel on the dual, for a few contact rows";
  toy.option_names = {"max_sweeps"};
  toy.solve = solve_toy;
  return toy;
}

// A block pressed onto a cylinder, coarse: a handful of contact rows, some in contact.
std::string tiny_scene() {
  return R"({"model": "plane_strain", "material": {"E": 1.0, "nu": 0.3},
    "body": {"shape": "rectangle", "width": 2.0, "height": 1.0, "symmetry": true,
             "mesh": {"size": 0.25, "contact_size": 0.1}},
    "load": {"type": "displacement", "boundary": "top", "value": [null, -0.02]},
    "obstacle": {"type": "circle", "center": [0.0, -1.0], "radius": 1.0},
    "solver": {"tol": 1e-10}})";
}

}  // namespace

TEST_CASE("a toy backend registered in one file is named, listed and solved like the built-ins",
          "[cross_backend][registry]") {
  const ScopedBackendRegistration registration(toy_backend());
  const Backend toy = registration.backend();
  CHECK(to_string(toy) == "toy");
  CHECK(parse_backend("toy") == toy);
  CHECK(backend_available(toy));
  CHECK(backend_supports(toy, ProblemKind::Frictionless));
  CHECK_FALSE(backend_supports(toy, ProblemKind::Tresca));
  const std::vector<Backend> listed = available_backends();
  CHECK(listed.back() == toy);  // order 1000: after the built-ins
  CHECK_THROWS_WITH(parse_backend("tyo"), Catch::Matchers::Contains("did you mean \"toy\""));

  SECTION("solve(): random QPs to their enumerated solution, certified") {
    const unsigned seed = GENERATE(range(1u, 4u));
    const QuadraticProgram qp = random_qp(8, 6, seed);
    const ExactSolution exact = solve_by_enumeration(qp);
    SolveOptions options = options_for(toy, 1e-10);
    const SolveResult r = solve(qp, options);
    CAPTURE(seed, r.message);
    REQUIRE(r.status == Status::Converged);
    CHECK(relative_difference(r.u, exact.u) < 1e-6);
    CHECK(relative_difference(r.lambda, exact.lambda) < 1e-5);
    const Certificate c = certify(qp, r.u, r.lambda, r.K_factor.get());
    CHECK(c.kkt_max() <= 1e-10);
    CHECK(std::abs(c.relative_gap) <= 1e-8);
  }
  SECTION("its options: its own key passes, another is refused naming it") {
    SolveOptions options = options_for(toy, 1e-8);
    options.backend_options["max_sweeps"] = "100";
    CHECK_NOTHROW(validate_options(options));
    options.backend_options["max_sweep"] = "3";
    CHECK_THROWS_WITH(validate_options(options), Catch::Matchers::Contains("backend option max_sweep") &&
                                                     Catch::Matchers::Contains("did you mean \"max_sweeps\""));
  }
  SECTION("compare_scene(): a tiny scene, against active_set") {
    CompareOptions options;
    options.backends = {toy, Backend::ActiveSet};
    const CompareReport report = compare_scene(parse_scene(tiny_scene()), options);
    REQUIRE(report.runs.size() == 2);
    CHECK(report.qp->n_constraints() >= 3);
    CHECK(report.qp->n_constraints() <= 40);
    for (const BackendRun& run : report.runs) {
      CAPTURE(to_string(run.backend), run.result.message);
      CHECK(run.result.status == Status::Converged);
      CHECK(run.certificate.kkt_max() <= 1e-9);
    }
    CHECK(report.runs[0].backend == toy);
    CHECK(report.agree);
    CHECK(report.runs[0].contact.contact_nodes > 0);
  }
}

TEST_CASE("a registration lasts its scope, and names are checked", "[cross_backend][registry]") {
  const size_t before = available_backends().size();
  {
    const ScopedBackendRegistration registration(toy_backend());
    CHECK(available_backends().size() == before + 1);
    CHECK_THROWS_WITH(register_backend(toy_backend()), Catch::Matchers::Contains("already registered"));
  }
  CHECK(available_backends().size() == before);
  CHECK_THROWS_WITH(parse_backend("toy"), Catch::Matchers::Contains("unknown backend"));
  BackendRegistration bad = toy_backend();
  bad.name = "Toy Backend";
  CHECK_THROWS_AS(register_backend(bad), InputError);
  bad.name = "toy";
  bad.solve = nullptr;
  CHECK_THROWS_WITH(register_backend(bad), Catch::Matchers::Contains("needs a solve"));
  bad.available = false;  // a backend whose library is absent: named and listed, never solved
  const ScopedBackendRegistration absent(bad);
  CHECK(parse_backend("toy") == absent.backend());
  CHECK_FALSE(backend_available(absent.backend()));
  CHECK_THROWS_WITH(solve(random_qp(4, 3, 1), options_for(absent.backend(), 1e-8)),
                    Catch::Matchers::Contains("was not built into this copy"));
}

TEST_CASE("solve() refuses a kind of problem its backend does not solve, naming those that do",
          "[cross_backend][registry]") {
  QuadraticProgram qp = random_qp(6, 3, 2);
  qp.friction.law = FrictionLaw::Tresca;
  qp.friction.n_directions = 1;
  qp.friction.T = qp.B;  // any m × n rows: the kind is refused before anyone reads them
  qp.friction.offset = VectorXd::Zero(qp.n_constraints());
  qp.friction.threshold = VectorXd::Ones(qp.n_constraints());
  CHECK(problem_kind(qp) == ProblemKind::Tresca);
  CHECK(problem_kind(random_qp(6, 3, 2)) == ProblemKind::Frictionless);

  const ScopedBackendRegistration frictionless(toy_backend());
  BackendRegistration tresca = toy_backend();
  tresca.name = "toy_tresca";
  tresca.problem_kinds = {ProblemKind::Frictionless, ProblemKind::Tresca};
  const ScopedBackendRegistration registration(tresca);
  CHECK(backend_supports(registration.backend(), ProblemKind::Tresca));
  const std::vector<Backend> solving = available_backends(ProblemKind::Tresca);
  CHECK(std::find(solving.begin(), solving.end(), registration.backend()) != solving.end());

  try {
    solve(qp, options_for(frictionless.backend(), 1e-8));
    FAIL("solve() accepted a Tresca problem for a frictionless backend");
  } catch (const InputError& error) {
    CHECK(error.field() == "backend");
    const std::string text = error.what();
    CHECK(text.find("\"toy\"") != std::string::npos);
    CHECK(text.find("tresca") != std::string::npos);
    CHECK(text.find("toy_tresca") != std::string::npos);
  }
}
