// run_scene() and compare_scene() (run.hpp): the pipeline as one call gives what its steps give
// when chained by hand, and its report owns its data.
#include <catch2/catch.hpp>
#include <memory>

#include "contactqp/certificate.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/run.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

TEST_CASE("run_scene equals the pipeline chained by hand and outlives its scene", "[unit][run]") {
  RunReport report;
  {
    auto scene = std::make_unique<Scene>(load_scene(source_path("scenes/hertz.json")));
    scene->solver.backend = Backend::ActiveSet;
    report = contactqp::run_scene(*scene);
  }  // the scene is gone: the report holds its own model and QP

  Scene scene = load_scene(source_path("scenes/hertz.json"));
  scene.solver.backend = Backend::ActiveSet;
  Model model = build_model(scene);
  const QuadraticProgram qp = assemble_qp(model);
  const SolveResult result = solve(qp, scene.solver);
  const ContactSummary contact = summarize_contact(model, qp, result.u, result.lambda);
  const auto hertz = compare_with_hertz(model, contact);

  REQUIRE(report.model);
  REQUIRE(report.qp);
  CHECK(report.model->mesh.n_nodes() == model.mesh.n_nodes());
  CHECK(report.qp->n_dofs() == qp.n_dofs());
  REQUIRE(report.result.status == Status::Converged);
  // Same inputs, same deterministic backend: the same numbers, to round-off.
  CHECK(relative_difference(report.result.u, result.u) < 1e-12);
  CHECK(relative_difference(report.result.lambda, result.lambda) < 1e-12);
  CHECK(report.contact.total_force == Approx(contact.total_force).epsilon(1e-12));
  REQUIRE(report.hertz);
  REQUIRE(hertz);
  CHECK(report.hertz->half_width == Approx(hertz->half_width).epsilon(1e-12));
  const Certificate c = certify(qp, result.u, result.lambda);
  CHECK(report.certificate.objective == Approx(c.objective).epsilon(1e-12));
  CHECK(report.certificate.kkt_max() < 1e-8);
  for (const char* phase : {"mesh", "assemble", "certify", "postprocess", "total"}) {
    CAPTURE(phase);
    CHECK(report.timings.has(phase));
  }
  CHECK(report.timings.get("total") >= report.timings.get("mesh"));
  CHECK_FALSE(report.options.observer);
}

TEST_CASE("run_scene calls the scene's observer and reports bad options before any work", "[unit][run]") {
  Scene scene = load_scene(source_path("scenes/hertz.json"));
  scene.solver.backend = Backend::Uzawa;
  int calls = 0;
  scene.solver.observer = [&](int, const VectorXd&, const VectorXd&) { ++calls; };
  const RunReport report = contactqp::run_scene(scene);
  CHECK(calls > 0);
  CHECK(calls <= report.result.iterations + 1);

  scene.solver.tol = -1;
  CHECK_THROWS_WITH(contactqp::run_scene(scene), Catch::Matchers::Contains("tol = -1"));
  CHECK_THROWS_WITH(contactqp::run_scene(std::string("/nonexistent/scene.json")),
                    Catch::Matchers::Contains("/nonexistent/scene.json"));
}

TEST_CASE("compare_scene: every available backend on one QP, certified by one factor", "[unit][run]") {
  Scene scene = load_scene(source_path("scenes/hertz.json"));
  scene.solver.tol = 1e-10;
  const CompareReport report = compare_scene(scene);
  REQUIRE(report.runs.size() == available_backends().size());
  CHECK(report.all_converged);
  CHECK(report.agree);
  REQUIRE(report.reference >= 0);
  for (const BackendRun& run : report.runs) {
    CAPTURE(to_string(run.backend));
    // The reference's answer checked independently: each run against the reference run.
    CHECK(relative_difference(run.result.u, report.runs[report.reference].result.u) <= report.bound.u);
    CHECK(run.certificate.kkt_max() < 1e-8);
    CHECK_FALSE(run.result.K_factor);
  }
  CompareOptions two;
  two.backends = {Backend::ActiveSet, Backend::Uzawa};
  const CompareReport pair = compare_scene(scene, two);
  REQUIRE(pair.runs.size() == 2);
  CHECK(pair.runs[0].backend == Backend::ActiveSet);
  CHECK(pair.runs[1].backend == Backend::Uzawa);
}
