// Friction on the petsc backend (bound_pdas.cpp's stick and slip states, docs/friction-backends.md)
// against active_set's semismooth Newton on the condensed problem, an independent method, along
// the shipped frictional scenes' load paths: every step certified, the last steps' u, λ_N and
// λ_T the same, the same nodes sticking and slipping. The small QPs with closed-form answers are
// test_friction_backends.cpp's, which reach petsc through available_backends() (2D and 3D).
#include <catch2/catch.hpp>

#include <string>

#include "contactqp/run.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

// Solves `scene` along its load path with active_set and petsc at tol 1e-10 and checks that
// they agree (compare_scene) and give the same last step.
void check_petsc_against_active_set(Scene scene) {
  scene.solver.tol = 1e-10;
  CompareOptions options;
  options.backends = {Backend::ActiveSet, Backend::Petsc};
  const CompareReport report = compare_scene(scene, options);
  REQUIRE(report.qp);
  REQUIRE(report.runs.size() == 2);
  CHECK(report.all_converged);
  CHECK(report.agree);
  const BackendRun& reference = report.runs[0];
  const BackendRun& petsc = report.runs[1];
  CAPTURE(reference.result.message, petsc.result.message);
  CHECK(petsc.result.status == Status::Converged);
  // Certified by the comparison's own factor of K, not by PETSc.
  CHECK(petsc.certificate.kkt_max() <= 10 * scene.solver.tol);
  CHECK(petsc.certificate.tangential <= 10 * scene.solver.tol);
  REQUIRE(petsc.result.lambda_t.size() == report.qp->friction.T.rows());
  CHECK(relative_difference(petsc.result.u, reference.result.u) <= 1e-6);
  CHECK(relative_difference(petsc.result.lambda, reference.result.lambda) <= 1e-5);
  CHECK(relative_difference(petsc.result.lambda_t, reference.result.lambda_t) <= 1e-5);
  // The same nodes stick and slip (active_set counts its last Tresca solve's states).
  CHECK(petsc.result.diagnostics.at("stick_nodes") == reference.result.diagnostics.at("stick_nodes"));
  CHECK(petsc.result.diagnostics.at("slip_nodes") == reference.result.diagnostics.at("slip_nodes"));
  CHECK(petsc.result.diagnostics.at("fixed_point_steps") >= 1);
  // One hierarchy for the whole path (BoundQpChain): the last step's Tresca solves set up none.
  CHECK(petsc.result.diagnostics.count("preconditioner_setups") == 0);
}

}  // namespace

TEST_CASE("petsc agrees with active_set along the 2D frictional scenes' load paths",
          "[cross_backend][petsc][friction]") {
  if (!backend_available(Backend::Petsc)) return;
  // sliding-block: a rigid plane, every bottom node slipping at the last step (Coulomb);
  // mindlin-on-plane: dissimilar materials, so some slip already under the normal push;
  // mindlin-cylinders: two bodies, stick and slip, each node's normal and tangential rows
  // changed together on its own DOFs. Coarser meshes than shipped, to keep the test short.
  const std::string name = GENERATE(as<std::string>{}, "scenes/sliding-block.json", "scenes/mindlin-on-plane.json",
                                    "scenes/mindlin-cylinders.json");
  CAPTURE(name);
  Scene scene = load_scene(source_path(name));
  if (name == "scenes/sliding-block.json") {
    scene.body.mesh.size = 0.25;
    scene.body.mesh.contact_size = 0.25;
  } else if (name == "scenes/mindlin-on-plane.json") {
    scene.body.mesh.contact_size = 2e-4;
  } else {
    for (SceneBody& body : scene.bodies) body.body.mesh.contact_size = 2e-4;
  }
  check_petsc_against_active_set(scene);
}

// 3D: each slipping node's direction follows the steps by Newton's method (bound_pdas.cpp's
// TangentialStates), some nodes pinned. Two hemispheres, node-to-node rows between bodies, a
// symmetry plane (rows with one tangential variable). Contact zone coarsened from 0.0085 to
// 0.025 (14 200 DOFs; at 0.04 active_set stalls). About 10 s, so [heavy].
TEST_CASE("petsc agrees with active_set along mindlin-spheres' load path (3D friction)",
          "[cross_backend][petsc][friction][heavy]") {
  if (!backend_available(Backend::Petsc)) return;
  Scene scene = load_scene(source_path("scenes/mindlin-spheres.json"));
  for (SceneBody& body : scene.bodies) body.body.mesh.contact_size = 0.025;
  check_petsc_against_active_set(scene);
}

// Load steps on one A: each step's solve continues the chain of the step before it
// (petsc_backend.cpp's solver of K carries it), so the path sets up one hierarchy in all and
// every later step starts from the last answer. The steps' answers are those of active_set's
// run (an independent method: the condensed problem, CHOLMOD), step by step.
TEST_CASE("petsc sets up one hierarchy along a frictional load path, and each step is active_set's",
          "[cross_backend][petsc][friction]") {
  if (!backend_available(Backend::Petsc)) return;
  const std::string name = GENERATE(as<std::string>{}, "scenes/mindlin-on-plane.json", "scenes/sliding-block.json");
  CAPTURE(name);
  Scene scene = load_scene(source_path(name));
  if (name == "scenes/sliding-block.json") {
    scene.body.mesh.size = 0.25;
    scene.body.mesh.contact_size = 0.25;
  } else {
    scene.body.mesh.contact_size = 2e-4;
  }
  scene.solver.tol = 1e-10;
  scene.estimate = false;
  REQUIRE(scene.steps.size() >= 2);
  scene.solver.backend = Backend::ActiveSet;
  const RunReport reference = run_scene(scene);
  scene.solver.backend = Backend::Petsc;
  const RunReport petsc = run_scene(scene);
  REQUIRE(reference.steps.size() == scene.steps.size());
  REQUIRE(petsc.steps.size() == scene.steps.size());
  double setups = 0;
  for (std::size_t k = 0; k < petsc.steps.size(); ++k) {
    CAPTURE(k, petsc.steps[k].message);
    const StepReport& step = petsc.steps[k];
    CHECK(step.status == Status::Converged);
    const auto found = step.diagnostics.find("preconditioner_setups");
    const double here = found == step.diagnostics.end() ? 0 : found->second;
    CHECK(here == (k == 0 ? 1 : 0));
    setups += here;
    const ContactSummary& mine = step.contact;
    const ContactSummary& theirs = reference.steps[k].contact;
    CHECK(mine.total_force == Approx(theirs.total_force).epsilon(1e-8));
    CHECK(mine.tangential_force == Approx(theirs.tangential_force).epsilon(1e-7).margin(1e-9 * theirs.total_force));
    CHECK(mine.stick_size == Approx(theirs.stick_size).epsilon(1e-8));
  }
  CHECK(setups == 1);
  REQUIRE(petsc.result.u.size() == reference.result.u.size());
  CHECK(relative_difference(petsc.result.u, reference.result.u) <= 1e-6);
  CHECK(relative_difference(petsc.result.lambda_t, reference.result.lambda_t) <= 1e-5);
}
