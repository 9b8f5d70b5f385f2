// The petsc backend (solvers/petsc.cpp, docs/petsc.md) against active_set on the shipped
// scenes, 2D and 3D, the nodes with two rows and several obstacles included; its alternative
// method (TAO); and what it reports: outer and Krylov iterations, PETSc's divergence reason,
// unused options, bad input. The mpirun runs are tests/tools/check_mpirun.py (ctest
// mpirun_petsc_hertz); the generic QPs of test_backends.cpp reach it through available_backends().
#include <catch2/catch.hpp>

#include "contactqp/certificate.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/model.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

bool petsc_built_in() { return backend_available(Backend::Petsc); }

// A patched scene is parsed from text, so it cannot name a Gmsh file relative to itself:
// unpatched scenes (strip-liftoff's strip.geo) are loaded from their own directory.
QuadraticProgram scene_qp(const std::string& relative, const std::string& patch = "{}") {
  Model model = build_model(patch == std::string("{}") ? load_scene(source_path(relative))
                                                       : parse_scene(patched_scene(relative, patch)));
  return assemble_qp(model);
}

SolveOptions petsc_options(double tol, const std::string& petsc = "", const std::string& method = "") {
  SolveOptions options = options_for(Backend::Petsc, tol);
  options.petsc_options = petsc;
  if (!method.empty()) options.backend_options["method"] = method;
  return options;
}

}  // namespace

TEST_CASE("petsc agrees with active_set on the shipped scenes, 2D and 3D", "[cross_backend][petsc][hertz]") {
  if (!petsc_built_in()) return;
  // disc-in-vgroove: two obstacles, nodes with a row for each (a per-node change of variables
  // that is not orthogonal); block-on-circle and strip-liftoff: rows that open; hertz-sphere:
  // 3D, six rigid-body modes (coarser, order 1, to keep the test short).
  const std::string scene =
      GENERATE(as<std::string>{}, "scenes/hertz.json", "scenes/disc-in-vgroove.json", "scenes/block-on-circle.json",
               "scenes/strip-liftoff.json", "scenes/hertz-sphere.json");
  const char* patch = scene == "scenes/disc-in-vgroove.json" ? R"({"body": {"mesh": {"contact_size": 0.01}}})"
                      : scene == "scenes/hertz-sphere.json"
                          ? R"({"body": {"mesh": {"contact_size": 0.03, "order": 1}}})"
                          : "{}";
  CAPTURE(scene);
  const QuadraticProgram qp = scene_qp(scene, patch);
  const double tol = 1e-10;
  SolveOptions reference_options = options_for(Backend::ActiveSet, tol);
  const SolveResult reference = solve(qp, reference_options);
  const SolveResult r = solve(qp, petsc_options(tol));
  CAPTURE(r.message);
  REQUIRE(reference.status == Status::Converged);
  REQUIRE(r.status == Status::Converged);
  CHECK(relative_difference(r.u, reference.u) <= 1e-6);
  CHECK(relative_difference(r.lambda, reference.lambda) <= 1e-5);
  // The same certificate, computed independently (CHOLMOD) of the PETSc solver that produced u.
  const Certificate c = certify(qp, r.u, r.lambda);
  CHECK(c.kkt_max() <= 10 * tol);
  CHECK(std::abs(c.relative_gap) <= 100 * tol);
  // Outer and inner iterations are reported; the certificate's solver of K is PETSc's.
  CHECK(r.iterations >= 1);
  CHECK(r.diagnostics.at("outer_iterations") == r.iterations);
  CHECK(r.diagnostics.at("krylov_iterations") >= r.diagnostics.at("linear_solves"));
  CHECK(r.diagnostics.at("active_constraints") > 0);
  REQUIRE(r.K_factor);
  CHECK(r.K_factor->statistics().name == "petsc");
  CHECK(r.warnings.empty());
}

TEST_CASE("petsc's alternative, TAO's bounded Newton on the same bound form, gives the same answer",
          "[cross_backend][petsc][hertz]") {
  if (!petsc_built_in()) return;
  const QuadraticProgram qp = scene_qp("scenes/hertz.json");
  const SolveResult reference = solve(qp, options_for(Backend::ActiveSet, 1e-10));
  const SolveResult r = solve(qp, petsc_options(1e-10, "", "tao"));
  CAPTURE(r.message);
  REQUIRE(r.status == Status::Converged);
  CHECK_THAT(r.message, Catch::Matchers::Contains("tao bnls"));
  CHECK(relative_difference(r.u, reference.u) <= 1e-6);
  CHECK(relative_difference(r.lambda, reference.lambda) <= 1e-5);
}

TEST_CASE("the petsc backend: divergence, unused and bad options, unavailability", "[petsc]") {
  const QuadraticProgram qp = scene_qp("scenes/hertz.json");
  if (!petsc_built_in()) {
    CHECK_THROWS_WITH(solve(qp, petsc_options(1e-8)), Catch::Matchers::Contains("not built"));
    return;
  }
  SECTION("a KSP stopped early is a numerical error with PETSc's reason") {
    const SolveResult r = solve(qp, petsc_options(1e-8, "-ksp_max_it 2"));
    CHECK(r.status == Status::NumericalError);
    CHECK_THAT(r.message, Catch::Matchers::Contains("KSP_DIVERGED_ITS"));
    CHECK(r.u.allFinite());
    CHECK(r.lambda.allFinite());
  }
  SECTION("an option nothing reads is our warning") {
    const SolveResult r = solve(qp, petsc_options(1e-8, "-contactqp_no_such_option 3"));
    CHECK(r.status == Status::Converged);
    REQUIRE(!r.warnings.empty());
    CHECK_THAT(r.warnings[0], Catch::Matchers::Contains("-contactqp_no_such_option 3"));
  }
  SECTION("an unknown KSP type and an unknown method are bad input") {
    CHECK_THROWS_WITH(solve(qp, petsc_options(1e-8, "-ksp_type nonsense")),
                      Catch::Matchers::StartsWith("petsc_options = \"-ksp_type nonsense\""));
    CHECK_THROWS_WITH(solve(qp, petsc_options(1e-8, "", "simplex")),
                      Catch::Matchers::Contains("method") && Catch::Matchers::Contains("valid: pdas, tao"));
  }
}

TEST_CASE("the CLI: --backend petsc, and a bad --linear-solver is bad input", "[petsc][cli]") {
  const std::string scene = source_path("scenes/hertz.json");
  const CliRun bad = run_cli("solve " + scene + " --linear-solver mumps");
  CHECK(bad.exit_status == 2);
  CHECK(std::count(bad.err.begin(), bad.err.end(), '\n') == 1);
  CHECK_THAT(bad.err, Catch::Matchers::Contains("--linear-solver") && Catch::Matchers::Contains("mumps"));
  if (!petsc_built_in()) return;
  const CliRun run = run_cli("solve " + scene + " --backend petsc --tol 1e-10");
  CHECK(run.exit_status == 0);
  CHECK_THAT(run.out, Catch::Matchers::Contains("Krylov iterations"));
}
