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
  // One hierarchy for all the Tresca solves of the last step's fixed point (BoundQpChain).
  CHECK(petsc.result.diagnostics.at("preconditioner_setups") == 1);
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
