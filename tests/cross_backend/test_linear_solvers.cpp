// One check, every solver of K: the backends that solve with K (uzawa, uzawa_accel, nlopt,
// active_set) with each available LinearSolverKind, against exact solutions of small QPs and
// against CHOLMOD on shipped scenes; then what the PETSc solver promises on its own: the
// certificate at tol, PETSc's divergence reason, unused options, bad options, the options of
// one solve not leaking into the next, PETSC_OPTIONS, and start/finish of PETSc in the CLI.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>

#include "contactqp/certificate.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/model.hpp"
#include "contactqp/petsc/par_qp.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

// The backends whose every solve goes through SolveOptions::linear_solver (Ipopt factorises
// its own KKT matrix with MUMPS).
const Backend kSolvingBackends[] = {Backend::Uzawa, Backend::UzawaAccelerated, Backend::Nlopt, Backend::ActiveSet};

std::vector<LinearSolverKind> available_linear_solvers() {
  std::vector<LinearSolverKind> list;
  for (LinearSolverKind kind : all_linear_solvers())
    if (linear_solver_available(kind)) list.push_back(kind);
  return list;
}

SolveOptions options_with(Backend backend, LinearSolverKind kind, double tol, const std::string& petsc_options = "") {
  SolveOptions options = options_for(backend, tol);
  options.linear_solver = kind;
  set_petsc_options(options, petsc_options);
  return options;
}

bool petsc_solver_built_in() { return linear_solver_available(LinearSolverKind::Petsc); }

}  // namespace

TEST_CASE("every backend with every solver of K solves random QPs to their enumerated solution",
          "[cross_backend][linear_solver]") {
  const Backend backend =
      GENERATE(from_range(std::vector<Backend>(std::begin(kSolvingBackends), std::end(kSolvingBackends))));
  const LinearSolverKind kind = GENERATE(from_range(available_linear_solvers()));
  const unsigned seed = GENERATE(range(200u, 203u));
  CAPTURE(to_string(backend), to_string(kind), seed);
  const QuadraticProgram qp = random_qp(8, 6, seed);
  const ExactSolution exact = solve_by_enumeration(qp);
  const SolveResult r = solve(qp, options_with(backend, kind, 1e-10));
  CAPTURE(r.message);
  REQUIRE(r.status == Status::Converged);
  CHECK(relative_difference(r.u, exact.u) < 1e-6);
  CHECK((r.lambda - exact.lambda).norm() < 1e-6 * std::max(1.0, exact.lambda.norm()));
  CHECK(certify(qp, r.u, r.lambda).kkt_max() < 1e-6);
}

TEST_CASE("each solver of K holds a spring against a wall", "[cross_backend][linear_solver]") {
  const Backend backend =
      GENERATE(from_range(std::vector<Backend>(std::begin(kSolvingBackends), std::end(kSolvingBackends))));
  const LinearSolverKind kind = GENERATE(from_range(available_linear_solvers()));
  CAPTURE(to_string(backend), to_string(kind));
  const double k = 3.0, F = 2.0, gap = 0.5;
  const SolveResult r = solve(spring_against_wall(k, F, gap), options_with(backend, kind, 1e-10));
  REQUIRE(r.status == Status::Converged);
  CHECK(r.u[0] == Approx(gap).epsilon(1e-8));
  CHECK(r.lambda[0] == Approx(F - k * gap).epsilon(1e-8));
}

TEST_CASE("with PETSc as the solver of K the backends give CHOLMOD's u on shipped scenes",
          "[cross_backend][linear_solver][hertz][heavy]") {
  if (!petsc_solver_built_in()) return;
  // hertz: the paper's problem; disc-in-vgroove (coarser at the contact, as test_scenes has
  // it, to keep the test short): two obstacles, nodes with a row for each; hertz-sphere (coarse
  // 4-node tetrahedra): 3D, GAMG with the six rigid-body modes.
  const std::string scene =
      GENERATE(as<std::string>{}, "scenes/hertz.json", "scenes/disc-in-vgroove.json", "scenes/hertz-sphere.json");
  const char* patch = scene == "scenes/hertz.json" ? "{}"
                      : scene == "scenes/disc-in-vgroove.json"
                          ? R"({"body": {"mesh": {"contact_size": 0.01}}})"
                          : R"({"body": {"mesh": {"contact_size": 0.03, "order": 1}}})";
  const QuadraticProgram qp = scene_qp(scene, patch);
  const double tol = 1e-10;
  for (Backend backend : kSolvingBackends) {
    CAPTURE(scene, to_string(backend));
    const SolveResult direct = solve(qp, options_with(backend, LinearSolverKind::Cholmod, tol));
    const SolveResult iterative = solve(qp, options_with(backend, LinearSolverKind::Petsc, tol));
    CAPTURE(iterative.message);
    REQUIRE(direct.status == Status::Converged);
    REQUIRE(iterative.status == Status::Converged);
    CHECK(relative_difference(iterative.u, direct.u) <= 1e-6);
    CHECK(relative_difference(iterative.lambda, direct.lambda) <= 1e-5);
    // The inner rule leaves a stationarity residual of at most tol/10 (docs/linear-solvers.md);
    // certified by CHOLMOD, independently of the solver that produced u.
    const Certificate c = certify(qp, iterative.u, iterative.lambda);
    CHECK(c.stationarity <= tol);
    CHECK(c.kkt_max() <= 10 * tol);
    CHECK(std::abs(c.relative_gap) <= 100 * tol);
    // The Krylov work is reported, and the solver is the one asked for.
    REQUIRE(iterative.K_factor);
    CHECK(iterative.K_factor->statistics().name == "petsc");
    CHECK(iterative.diagnostics.at("krylov_iterations") >= iterative.diagnostics.at("linear_solves"));
    CHECK(iterative.warnings.empty());
  }
}

TEST_CASE("the PETSc solver of K: divergence, unused and bad options, no leaks between solves",
          "[linear_solver][petsc]") {
  const QuadraticProgram qp = scene_qp("scenes/hertz.json");
  if (!petsc_solver_built_in()) {
    CHECK_THROWS_WITH(solve(qp, options_with(Backend::Uzawa, LinearSolverKind::Petsc, 1e-8)),
                      Catch::Matchers::Contains("linear_solver = petsc") && Catch::Matchers::Contains("not built"));
    return;
  }
  SECTION("a KSP stopped before the inner tolerance is a numerical error with PETSc's reason") {
    const SolveResult r = solve(qp, options_with(Backend::Uzawa, LinearSolverKind::Petsc, 1e-8, "-ksp_max_it 3"));
    CHECK(r.status == Status::NumericalError);
    CHECK_THAT(r.message, Catch::Matchers::Contains("KSP_DIVERGED_ITS"));
    CHECK(r.u.allFinite());
    // The next solve does not inherit -ksp_max_it 3.
    const SolveResult next = solve(qp, options_with(Backend::ActiveSet, LinearSolverKind::Petsc, 1e-8));
    CHECK(next.status == Status::Converged);
  }
  SECTION("an option nothing reads is a warning, as PETSc's -options_left would say") {
    const SolveResult r =
        solve(qp, options_with(Backend::ActiveSet, LinearSolverKind::Petsc, 1e-8, "-contactqp_no_such_option 7"));
    CHECK(r.status == Status::Converged);
    REQUIRE(r.warnings.size() == 1);
    CHECK_THAT(r.warnings[0], Catch::Matchers::Contains("-contactqp_no_such_option 7"));
  }
  SECTION("options reach PETSc unchanged: another Krylov method and preconditioner") {
    const SolveResult direct = solve(qp, options_with(Backend::ActiveSet, LinearSolverKind::Cholmod, 1e-10));
    const SolveResult r = solve(qp, options_with(Backend::ActiveSet, LinearSolverKind::Petsc, 1e-10,
                                                 "-ksp_type gmres -pc_gamg_threshold 0.01"));
    REQUIRE(r.status == Status::Converged);
    CHECK(r.K_factor->statistics().method.rfind("gmres + gamg", 0) == 0);
    CHECK(r.warnings.empty());  // -pc_gamg_threshold was read
    CHECK(relative_difference(r.u, direct.u) <= 1e-6);
  }
  SECTION("an unknown KSP type is bad input naming petsc_options") {
    CHECK_THROWS_AS(solve(qp, options_with(Backend::Uzawa, LinearSolverKind::Petsc, 1e-8, "-ksp_type nonsense")),
                    InputError);
    CHECK_THROWS_WITH(
        solve(qp, options_with(Backend::Uzawa, LinearSolverKind::Petsc, 1e-8, "-ksp_type nonsense")),
        Catch::Matchers::StartsWith("petsc_options = \"-ksp_type nonsense\"") && Catch::Matchers::Contains("nonsense"));
  }
}

TEST_CASE("the CLI passes PETSc options through, reads PETSC_OPTIONS, and ends PETSc on every exit",
          "[linear_solver][petsc][cli]") {
  const std::string scene = source_path("scenes/hertz.json");
  if (!petsc_solver_built_in()) {
    const CliRun run = run_cli("solve " + scene + " --linear-solver petsc");
    CHECK(run.exit_status == 2);
    CHECK_THAT(run.err, Catch::Matchers::Contains("not built"));
    return;
  }
  // -log_view is printed by PetscFinalize: it ran, at exit.
  const CliRun logged =
      run_cli("solve " + scene + " --backend active_set --linear-solver petsc --petsc-options=-log_view");
  CHECK(logged.exit_status == 0);
  CHECK_THAT(logged.out, Catch::Matchers::Contains("KSPSolve"));
  // The environment variable, as PETSc users expect (set for the child process only: this
  // process's PETSc would read it too).
  ::setenv("PETSC_OPTIONS", "-ksp_max_it 2", 1);
  const CliRun limited = run_cli("solve " + scene + " --linear-solver petsc");
  ::unsetenv("PETSC_OPTIONS");
  CHECK(limited.exit_status == 1);
  CHECK_THAT(limited.out, Catch::Matchers::Contains("KSP_DIVERGED_ITS"));
  // Bad input after PETSc started: one line, exit 2, PETSc and MPI ended cleanly.
  const CliRun bad = run_cli("solve " + scene + " --linear-solver petsc --petsc-options=\"-ksp_type nonsense\"");
  CHECK(bad.exit_status == 2);
  CHECK(std::count(bad.err.begin(), bad.err.end(), '\n') == 1);
  CHECK_THAT(bad.err, Catch::Matchers::Contains("petsc_options"));
  // An empty value makes CLI11 take the next argument: one of ours is refused, not passed on.
  const CliRun swallowed = run_cli("solve " + scene + " --linear-solver petsc --petsc-options= --verbose");
  CHECK(swallowed.exit_status == 2);
  CHECK_THAT(swallowed.err, Catch::Matchers::Contains("--petsc-options = \"--verbose\""));
  // compare takes the options too, and reports an unused option once.
  const CliRun compare =
      run_cli("compare " + scene +
              " --backends uzawa_accel,active_set --linear-solver petsc --petsc-options=\"-no_such_thing 1\"");
  CHECK(compare.exit_status == 0);
  const std::string warning = "PETSc option -no_such_thing 1 was not used";
  CHECK(compare.err.find(warning) != std::string::npos);
  CHECK(compare.err.find(warning) == compare.err.rfind(warning));
}
