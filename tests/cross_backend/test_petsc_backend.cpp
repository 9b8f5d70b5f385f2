// The petsc backend (solvers/petsc.cpp, docs/petsc.md) against active_set on the shipped
// scenes, 2D and 3D, the nodes with two rows and several obstacles included; its alternative
// method (TAO); and what it reports: outer and Krylov iterations, PETSc's divergence reason,
// unused options, bad input; K assembled in rank shares and the mesh partition behind them. The
// mpirun runs are tests/tools/check_mpirun.py (ctest mpirun_petsc_hertz, _sphere); the generic QPs of test_backends.cpp reach it through available_backends().
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <vector>

#include "contactqp/certificate.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/model.hpp"
#include "contactqp/petsc/par_qp.hpp"
#include "contactqp/processes.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

bool petsc_backend_built_in() { return backend_available(Backend::Petsc); }

SolveOptions petsc_options(double tol, const std::string& petsc = "", const std::string& method = "") {
  SolveOptions options = options_for(Backend::Petsc, tol);
  set_petsc_options(options, petsc);
  if (!method.empty()) options.backend_options["method"] = method;
  return options;
}

// r converged to the reference's answer: u to 1e-6 and λ to 1e-5 relative.
void check_same_answer(const SolveResult& r, const SolveResult& reference) {
  CAPTURE(r.message);
  REQUIRE(r.status == Status::Converged);
  CHECK(relative_difference(r.u, reference.u) <= 1e-6);
  CHECK(relative_difference(r.lambda, reference.lambda) <= 1e-5);
}

}  // namespace

TEST_CASE("petsc agrees with active_set on the shipped scenes, 2D and 3D", "[cross_backend][petsc][hertz]") {
  if (!petsc_backend_built_in()) return;
  // disc-in-vgroove: two obstacles, nodes with a row for each (a per-node change of variables
  // that is not orthogonal); block-on-circle and strip-liftoff: rows that open; hertz-sphere:
  // 3D, six rigid-body modes (coarser, order 1, to keep the test short); hertz-order2: 6-node
  // triangles, so the P1 level, its start and its truncated hierarchy (0.1 s); two-cylinders:
  // rows between two bodies, each node's change of variables on its own DOFs (bound_form.hpp).
  const std::string scene = GENERATE(
      as<std::string>{}, "scenes/hertz.json", "scenes/disc-in-vgroove.json", "scenes/block-on-circle.json",
      "scenes/strip-liftoff.json", "scenes/hertz-sphere.json", "scenes/hertz-order2.json", "scenes/two-cylinders.json");
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
  CHECK(r.diagnostics.at("preconditioner_setups") == 1);  // one hierarchy, kept across the steps
  if (scene == "scenes/hertz-order2.json") {
    CHECK_THAT(r.message, Catch::Matchers::Contains("P1 level") && Catch::Matchers::Contains("P1 start"));
    CHECK(r.diagnostics.at("p1_start_steps") >= 1);
  }

  // The loop with a set-up per step (hierarchy=fresh): the same answer.
  SolveOptions fresh = petsc_options(tol);
  fresh.backend_options["hierarchy"] = "fresh";
  const SolveResult k = solve(qp, fresh);
  check_same_answer(k, reference);
  CHECK(certify(qp, k.u, k.lambda).kkt_max() <= 10 * tol);
  CHECK(k.diagnostics.at("preconditioner_setups") == k.diagnostics.at("linear_solves"));
}

TEST_CASE("petsc's alternative, TAO's bounded Newton on the same bound form, gives the same answer",
          "[cross_backend][petsc][hertz]") {
  if (!petsc_backend_built_in()) return;
  const QuadraticProgram qp = scene_qp("scenes/hertz.json");
  const SolveResult reference = solve(qp, options_for(Backend::ActiveSet, 1e-10));
  const SolveResult r = solve(qp, petsc_options(1e-10, "", "tao"));
  check_same_answer(r, reference);
  CHECK_THAT(r.message, Catch::Matchers::Contains("tao bnls"));
}

TEST_CASE("the petsc backend: divergence, unused and bad options, unavailability", "[petsc]") {
  const QuadraticProgram qp = scene_qp("scenes/hertz.json");
  if (!petsc_backend_built_in()) {
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
  SECTION("loose_reduction changes the path, not the answer; outside (0, 1) it is bad input") {
    const SolveResult reference = solve(qp, options_for(Backend::ActiveSet, 1e-10));
    SolveOptions loose = petsc_options(1e-10);
    loose.backend_options["loose_reduction"] = "0.5";
    check_same_answer(solve(qp, loose), reference);
    for (const char* bad : {"1", "0", "-0.1", "ten"}) {
      INFO(bad);
      loose.backend_options["loose_reduction"] = bad;
      CHECK_THROWS_WITH(solve(qp, loose), Catch::Matchers::StartsWith("backend option loose_reduction"));
    }
  }
}

TEST_CASE("the CLI: --backend petsc, and a bad --linear-solver is bad input", "[petsc][cli]") {
  const std::string scene = source_path("scenes/hertz.json");
  const CliRun bad = run_cli("solve " + scene + " --linear-solver mumps");
  CHECK(bad.exit_status == 2);
  CHECK(std::count(bad.err.begin(), bad.err.end(), '\n') == 1);
  CHECK_THAT(bad.err, Catch::Matchers::Contains("--linear-solver") && Catch::Matchers::Contains("mumps"));
  if (!petsc_backend_built_in()) return;
  const CliRun run = run_cli("solve " + scene + " --backend petsc --tol 1e-10");
  CHECK(run.exit_status == 0);
  CHECK_THAT(run.out, Catch::Matchers::Contains("Krylov iterations"));
  // An option that ends the process inside hypre 2.26 on the PETSc solver of K: bad input.
  const CliRun crash = run_cli("solve " + scene +
                               " --no-contact --linear-solver petsc --petsc-options=\"-pc_type hypre "
                               "-pc_hypre_boomeramg_vec_interp_variant 3\"");
  CHECK(crash.exit_status == 2);
  CHECK(std::count(crash.err.begin(), crash.err.end(), '\n') == 1);
  CHECK_THAT(crash.err, Catch::Matchers::Contains("vec_interp_variant"));
}

TEST_CASE("K in rank shares: the shares of two ranks sum to the whole K, f stays whole, the rows are a permutation",
          "[petsc][mpi]") {
  if (!petsc_backend_built_in()) return;
  // On one process the two shares are assembled one after the other, the second on the rows
  // the first chose: what the two ranks of `mpirun -n 2` hold after their one collective
  // partition. two-cylinders-force: a rigid surface's DOFs share one column, which gets one row;
  // block-moment: a turning surface's angle, a column with no DOF of its own, gets one too.
  for (const char* scene : {"scenes/hertz.json", "scenes/hertz-sphere.json", "scenes/two-cylinders-force.json",
                            "scenes/block-moment.json"}) {
    INFO(scene);
    Model model = build_model(load_scene(source_path(scene)));
    const QuadraticProgram whole = assemble_qp(model);
    const ParQuadraticProgram first_rank = assemble_par_qp(model, RankShare{0, 2, {}});
    const ParQuadraticProgram second_rank = assemble_par_qp(model, RankShare{1, 2, first_rank.distributed_row});
    CHECK(first_rank.ranks == 2);
    CHECK(second_rank.rank == 1);
    const QuadraticProgram& first = first_rank.share;
    const QuadraticProgram& second = second_rank.share;
    const SparseMatrix sum = first.K + second.K;
    const double scale = whole.K.coeffs().cwiseAbs().maxCoeff();
    CHECK(SparseMatrix(sum - whole.K).coeffs().cwiseAbs().maxCoeff() <= 1e-14 * scale);
    CHECK(first.f == whole.f);  // bit for bit: every rank moves all prescribed displacements
    CHECK(second.f == whole.f);
    // Each share holds about half of K: the partition keeps the boundary between them small.
    CHECK(first.K.nonZeros() <= 0.6 * whole.K.nonZeros());
    CHECK(second.K.nonZeros() <= 0.6 * whole.K.nonZeros());
    std::vector<int> rows = first_rank.distributed_row;
    REQUIRE(static_cast<int>(rows.size()) == whole.n_dofs());
    std::sort(rows.begin(), rows.end());
    for (int i = 0; i < whole.n_dofs(); ++i) REQUIRE(rows[i] == i);
  }
}

TEST_CASE("partition_graph splits a path of 1000 vertices into two halves with one edge between them", "[petsc][mpi]") {
  if (!petsc_backend_built_in()) return;
  const int n = 1000;
  std::vector<long> offsets{0};
  std::vector<int> neighbours;
  for (int v = 0; v < n; ++v) {
    if (v > 0) neighbours.push_back(v - 1);
    if (v + 1 < n) neighbours.push_back(v + 1);
    offsets.push_back(static_cast<long>(neighbours.size()));
  }
  const std::vector<int> part = partition_graph(offsets, neighbours, 2);
  REQUIRE(static_cast<int>(part.size()) == n);
  int in_first = 0, cut = 0;
  for (int v = 0; v < n; ++v) {
    in_first += part[v] == 0;
    if (v + 1 < n) cut += part[v] != part[v + 1];
  }
  CHECK(std::abs(in_first - n / 2) <= n / 20);  // PT-Scotch balances to a few per cent
  CHECK(cut <= 2);
}
