// Loads by force on a rigid surface (docs/scene.md, "Force on a rigid surface"): a boundary whose
// nodes share one unknown displacement per tied component and carry a prescribed resultant.
// The independent truth is the displacement-driven run on the same mesh: the QP with the surface
// pushed by δ has the same solution as the QP with the force P(δ) that push gives, so a, p0, the
// contact force and the surface's displacement must agree with it to the solver's tolerance.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "contactqp/post.hpp"
#include "contactqp/run.hpp"
#include "contactqp/solve.hpp"
#include "every_backend.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

// A number as JSON text with every digit (the force that a push gives, handed back exactly).
std::string exact_digits(double x) { return nlohmann::json(x).dump(); }

RunReport run_force_patched(const std::string& scene, const std::string& patch) {
  return run_scene(parse_scene(patched_scene(scene, patch)), RunOptions{});
}

const Reaction& rigid_surface_of(const RunReport& report) {
  for (const Reaction& r : report.reactions)
    if (r.rigid_surface()) return r;
  FAIL("no rigid surface among the reactions");
  return report.reactions.front();
}

// The largest difference of two runs' nodal displacements on the same mesh, relative to the largest.
double nodal_difference_of(const RunReport& a, const RunReport& b) {
  const Eigen::VectorXd ua = full_displacement(*a.model, a.result.u);
  const Eigen::VectorXd ub = full_displacement(*b.model, b.result.u);
  REQUIRE(ua.size() == ub.size());
  return (ua - ub).cwiseAbs().maxCoeff() / ua.cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("a half cylinder pressed by a force on its rigid cut: the answer of the push that gives that force",
          "[validation][force_control]") {
  const RunReport pushed = run_force_patched("scenes/hertz.json", R"({"solver": {"backend": "active_set"}})");
  REQUIRE(pushed.result.status == Status::Converged);
  const double P = pushed.contact.total_force;  // the whole cylinder's, per length
  const RunReport forced =
      run_force_patched("scenes/hertz-force.json", R"({"load": {"value": [null, )" + exact_digits(-P) + "]}}");
  INFO(forced.result.message);
  REQUIRE(forced.result.status == Status::Converged);
  CHECK(forced.qp->null_space.cols() == 1);               // the cut's translation along y: only the plane holds it
  CHECK(forced.qp->n_dofs() == pushed.qp->n_dofs() + 1);  // the cut's y DOFs, one unknown instead of none

  const Reaction& surface = rigid_surface_of(forced);
  CHECK_FALSE(surface.displacement[0].has_value());  // null: each node free sideways, as the push leaves it
  REQUIRE(surface.displacement[1].has_value());
  CHECK(*surface.displacement[1] == Approx(-0.016).epsilon(1e-6));
  CHECK(surface.force.y() == Approx(-P).epsilon(1e-15));
  CHECK(forced.contact.total_force == Approx(P).epsilon(1e-8));
  CHECK(forced.contact.half_width == Approx(pushed.contact.half_width).epsilon(1e-6));
  CHECK(forced.contact.max_pressure == Approx(pushed.contact.max_pressure).epsilon(1e-6));
  CHECK(nodal_difference_of(forced, pushed) < 1e-6);
  REQUIRE(forced.hertz.has_value());
  REQUIRE(pushed.hertz.has_value());
  CHECK(forced.hertz->error_half_width == Approx(pushed.hertz->error_half_width).margin(1e-6));
  CHECK(forced.hertz->error_max_pressure == Approx(pushed.hertz->error_max_pressure).margin(1e-6));
}

TEST_CASE("the force turns with the scene: the cylinder turned by 30 degrees gives the same answer",
          "[validation][force_control]") {
  // The tied component stays along the scene's own y, as a push's does; the reported force is in
  // global axes, the displacement along the value's components.
  const RunReport upright = run_force_patched("scenes/hertz-force.json", "{}");
  const RunReport turned = run_force_patched("scenes/hertz-force.json", R"({"transform": {"rotate_degrees": 30}})");
  INFO(turned.result.message);
  REQUIRE(turned.result.status == Status::Converged);
  CHECK(*rigid_surface_of(turned).displacement[1] == Approx(*rigid_surface_of(upright).displacement[1]).epsilon(1e-6));
  CHECK(turned.contact.total_force == Approx(upright.contact.total_force).epsilon(1e-8));
  CHECK(turned.contact.half_width == Approx(upright.contact.half_width).epsilon(1e-6));
  CHECK(turned.contact.max_pressure == Approx(upright.contact.max_pressure).epsilon(1e-6));
  const double P = upright.contact.total_force;
  CHECK(rigid_surface_of(turned).force.x() == Approx(P * std::sin(M_PI / 6)).epsilon(1e-12));
  CHECK(rigid_surface_of(turned).force.y() == Approx(-P * std::cos(M_PI / 6)).epsilon(1e-12));
}

TEST_CASE("every backend solves the cylinder pressed by a force alike", "[validation][force_control][cross_backend]") {
  const std::string coarse = R"({"body": {"mesh": {"size": 0.2, "contact_size": 0.01}}})";
  const Scene scene = parse_scene(patched_scene("scenes/hertz-force.json", coarse));
  Model model = build_model(scene);
  const QuadraticProgram qp = assemble_qp(model);
  SolveOptions options = scene.solver;
  const SolveResult reference = solve(qp, options);
  REQUIRE(reference.status == Status::Converged);
  CHECK(every_backend_agrees(qp, options, reference) >= 3);
}

TEST_CASE("a force path: each step's rigid displacement, the last the one-shot answer",
          "[validation][force_control][steps]") {
  const RunReport one_shot = run_force_patched("scenes/hertz-force.json", "{}");
  const RunReport path = run_force_patched("scenes/hertz-force.json", R"({"load": {"name": "press"},
        "steps": [{"factors": {"press": 0.25}}, {"factors": {"press": 0.5}}, {"factors": {"press": 1}}]})");
  INFO(path.result.message);
  REQUIRE(path.result.status == Status::Converged);
  REQUIRE(path.steps.size() == 3);
  double last = 0;
  for (const StepReport& step : path.steps) {
    const Reaction* surface = nullptr;
    for (const Reaction& r : step.reactions)
      if (r.rigid_surface()) surface = &r;
    REQUIRE(surface != nullptr);
    const double P = step.contact.total_force;
    CHECK(-surface->force.y() == Approx(P).epsilon(1e-8));  // the surface carries this step's force
    const double delta = -*surface->displacement[1];
    CHECK(delta > last);  // a larger force pushes further ...
    last = delta;
  }
  // The last step is the one-shot solve: the same force, the same answer.
  const double d_last = -*rigid_surface_of(path).displacement[1];
  CHECK(-d_last == Approx(*rigid_surface_of(one_shot).displacement[1]).epsilon(1e-6));
  CHECK(path.contact.half_width == Approx(one_shot.contact.half_width).epsilon(1e-6));
}

TEST_CASE("a force that pulls the cylinder off the plane ends unbounded and names the motion",
          "[validation][force_control]") {
  const RunReport pulled = run_force_patched("scenes/hertz-force.json", R"({"load": {"value": [null, 0.001]}})");
  CHECK(pulled.result.status == Status::Unbounded);
  CHECK_THAT(pulled.result.message, Catch::StartsWith("unbounded: the body moves freely along +y"));
}

TEST_CASE("two cylinders pressed by a force: the answer of the push that gives that force",
          "[validation][force_control][bodies]") {
  const RunReport pushed = run_scene(load_scene(source_path("scenes/two-cylinders.json")), RunOptions{});
  REQUIRE(pushed.pairs.size() == 1);
  const double P = pushed.pairs[0].force_on_node_body.y();
  const RunReport forced =
      run_force_patched("scenes/two-cylinders-force.json",
                        R"({"bodies": [{"name": "roller", "shape": "half_disc", "radius": 1.0, "symmetry": true,
           "mesh": {"size": 0.1, "contact_size": 0.002}, "material": {"E": 1.0, "nu": 0.3},
           "load": {"type": "force", "boundary": "top", "value": [null, )" +
                            exact_digits(-P) + R"(]}},
         {"name": "base", "shape": "half_disc", "radius": 2.0, "symmetry": true, "mirror": true,
          "mesh": {"size": 0.2, "contact_size": 0.002}, "material": {"E": 2.0, "nu": 0.25},
          "load": {"type": "displacement", "boundary": "top", "value": [null, 0.0]}}]})");
  INFO(forced.result.message);
  REQUIRE(forced.result.status == Status::Converged);
  REQUIRE(forced.pairs.size() == 1);
  CHECK(forced.pairs[0].force_on_node_body.y() == Approx(P).epsilon(1e-8));
  CHECK(forced.pairs[0].half_width == Approx(pushed.pairs[0].half_width).epsilon(1e-6));
  CHECK(forced.pairs[0].max_pressure == Approx(pushed.pairs[0].max_pressure).epsilon(1e-6));
  CHECK(*rigid_surface_of(forced).displacement[1] == Approx(-0.016).epsilon(1e-6));
  CHECK(nodal_difference_of(forced, pushed) < 1e-6);
}

TEST_CASE("Hertz's half ball pressed by a force on its rigid top: the answer of the push that gives that force",
          "[validation][force_control][3d][heavy]") {
  const RunReport pushed = run_force_patched("scenes/hertz-sphere.json", "{}");
  REQUIRE(pushed.result.status == Status::Converged);
  const double P = pushed.contact.total_force;  // the whole ball's (4 × the quarter's)
  const RunReport forced = run_force_patched("scenes/hertz-sphere-force.json",
                                             R"({"load": {"value": [null, null, )" + exact_digits(-P) + "]}}");
  INFO(forced.result.message);
  REQUIRE(forced.result.status == Status::Converged);
  CHECK(*rigid_surface_of(forced).displacement[2] == Approx(-0.01).epsilon(1e-6));
  // The free translation's balance holds to the certificate's stationarity (6e-8 here, within
  // 10 × tol), not to round-off as in 2D: the force to 1e-6 (measured 6e-8).
  CHECK(forced.contact.total_force == Approx(P).epsilon(1e-6));
  CHECK(forced.contact.contact_radius == Approx(pushed.contact.contact_radius).epsilon(1e-6));
  CHECK(forced.contact.max_pressure == Approx(pushed.contact.max_pressure).epsilon(1e-6));
  CHECK(nodal_difference_of(forced, pushed) < 1e-6);
}

TEST_CASE("a force on a rigid surface: bad input exits 2 with one line naming the field",
          "[validation][force_control][cli][input]") {
  TemporaryDirectory directory;
  const auto refused = [&](const std::string& patch, const std::string& line) {
    const std::string scene = directory.path("bad.json");
    std::ofstream(scene) << patched_scene("scenes/hertz-force.json", patch);
    const CliRun r = run_cli("solve " + scene + " --json " + directory.path("out.json"));
    INFO(patch << "\n" << r.err);
    CHECK(r.exit_status == 2);
    CHECK(r.err == "contactqp: error: " + line + "\n");
    CHECK_FALSE(std::filesystem::exists(directory.path("out.json")));
  };
  refused(R"({"load": {"value": [null, null]}})",
          "load.value = [null, null]: give at least one component of the force (null leaves a component free)");
  refused(R"({"load": {"value": [-0.001]}})", "load.value = [-0.001]: must be [Fx, Fy], a component null when free");
  refused(R"({"load": {"value": [0, -0.001]}})",
          "body.symmetry = true: load ties the rigid surface along x (Fx = 0; give null: the plane holds x), which "
          "is not mirror-symmetric about x = 0; set \"symmetry\": false");
  refused(R"({"load": [{"type": "force", "boundary": "top", "value": [null, -0.001]},
                      {"type": "displacement", "boundary": "top", "value": [null, -0.01]}]})",
          "load[0].value[1] = -0.001 ties \"top\" along y as one rigid surface, but node 719 there is prescribed (to "
          "-0.01) by another condition; give null for this component");
}
