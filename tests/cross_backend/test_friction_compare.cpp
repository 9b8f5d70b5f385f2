// compare_scene() on a frictional scene with load steps: each backend runs the whole load path
// (with friction the answer depends on it) and the last steps agree and are certified.
#include <catch2/catch.hpp>

#include "contactqp/run.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

// compare_scene() at tol 1e-10: every backend that supports the scene runs its load path,
// converges (its certificate within 1e-8) and agrees with the others.
CompareReport compare_every_backend(Scene scene) {
  scene.solver.tol = 1e-10;
  CompareReport report = compare_scene(scene);
  REQUIRE(report.qp);
  CHECK(report.runs.size() == available_backends(*report.qp).size());
  CHECK(report.all_converged);
  CHECK(report.agree);
  for (const BackendRun& run : report.runs) {
    CAPTURE(to_string(run.backend), run.result.message);
    CHECK(run.result.status == Status::Converged);
    CHECK(run.result.lambda_t.size() == report.qp->friction.T.rows());
    CHECK(run.certificate.kkt_max() < 1e-8);
    CHECK(run.result.diagnostics.count("fixed_point_steps") == 1);
  }
  return report;
}

}  // namespace

TEST_CASE("compare runs every supporting backend's load path on a frictional scene", "[cross_backend][friction]") {
  Scene scene = load_scene(source_path("scenes/sliding-block.json"));
  scene.body.mesh.size = 0.25;  // coarse: about a second for all backends
  scene.body.mesh.contact_size = 0.25;
  scene.steps.resize(3);  // push, then two shear steps (0.1, 0.2): part of the bottom slips
  const CompareReport report = compare_every_backend(scene);
  // The last step's QP: its loads are the third step's, not the scene's in full.
  Model full = build_model(scene);
  const QuadraticProgram all_loads = assemble_qp(full);
  CHECK((all_loads.g - report.qp->g).norm() + (all_loads.f - report.qp->f).norm() > 0);
}

// A zone of one node, pushed onto the plane it starts on, that sticks: its rows' gap and slip
// are 0 at the answer, so a length scale made of the rows alone is round-off, and active_set's
// stopping rule (its natural map's ρ = F/L) turned round-off slips into residuals of 0.03 and
// stalled (solvers/active_set_friction.cpp, condensed_residual). Every backend must agree.
TEST_CASE("compare agrees on a frictional zone of one sticking node", "[cross_backend][friction]") {
  Scene scene = load_scene(source_path("scenes/mindlin-on-plane.json"));
  scene.body.mesh.contact_size = scene.body.mesh.size;  // 0.1 everywhere: one node in contact
  const CompareReport report = compare_every_backend(scene);
  CHECK(report.qp->n_constraints() == 1);
}
