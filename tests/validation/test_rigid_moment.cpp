// A moment on a rigid surface (docs/scenes.md, "Moment on a rigid surface"): the surface turns
// by one unknown angle per axis, u_i = t + θ × (x_i − c), and carries the moment about c.
// The independent truths: beam theory, exact for a block on a frictionless plane while the
// whole base presses (its stress is linear, which quadratic elements represent exactly), and
// statics, which any answer must meet: the contact forces balance the force and the moment.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "contactqp/post.hpp"
#include "contactqp/run.hpp"
#include "contactqp/solve.hpp"
#include "every_backend.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

RunReport run_patched(const std::string& scene, const std::string& patch) {
  return run_scene(parse_scene(patched_scene(scene, patch)), RunOptions{});
}

const Reaction& turning_surface_of(const RunReport& report) {
  for (const Reaction& r : report.reactions)
    if (r.turns()) return r;
  FAIL("no turning surface among the reactions");
  return report.reactions.front();
}

// The contact forces' resultant and moment about c: λ_i along the plane's normal at each candidate.
struct Balance {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
};
Balance contact_balance(const RunReport& report, const Eigen::Vector3d& normal, const Eigen::Vector3d& c) {
  Balance out;
  const Model& model = *report.model;
  for (std::size_t i = 0; i < model.candidates.size(); ++i) {
    const Eigen::Vector3d f = report.result.lambda[static_cast<long>(i)] * normal;
    out.force += f;
    out.moment += (model.mesh.nodes[model.candidates[i].node] - c).cross(f);
  }
  return out;
}

// The block of scenes/block-moment.json: W = 2, H = 1, E = 1, ν = 0.3, plane strain.
constexpr double kWidth = 2, kHeight = 1, kStiffness = 1 / (1 - 0.3 * 0.3);  // E' = E / (1 − ν²)

}  // namespace

TEST_CASE("a block tilted by a moment on its rigid top: beam theory's linear pressure, exact with 6-node triangles",
          "[validation][force_control][moment]") {
  for (const double M : {0.002, -0.0015, 0.0}) {  // within the kern |M| <= P W / 6 = 0.00333
    const double P = 0.01;
    const RunReport run = run_patched("scenes/block-moment.json", R"({"load": {"moment": )" + std::to_string(M) + "}}");
    INFO("M = " << M << ": " << run.result.message);
    REQUIRE(run.result.status == Status::Converged);
    const Reaction& top = turning_surface_of(run);
    CHECK_FALSE(top.displacement[0].has_value());  // free sideways at each node
    REQUIRE(top.displacement[1].has_value());
    REQUIRE(top.rotation[2].has_value());
    CHECK(top.moment.z() == M);
    CHECK(top.about.isApprox(Eigen::Vector3d(0, kHeight, 0)));  // the top's centroid
    // σ_yy = −P/W + 12 M x / W³ through the height: the top sinks by H P / (E' W) and turns by
    // 12 H M / (E' W³).
    CHECK(*top.displacement[1] == Approx(-kHeight * P / (kStiffness * kWidth)).epsilon(1e-8));
    CHECK(*top.rotation[2] == Approx(12 * kHeight * M / (kStiffness * std::pow(kWidth, 3))).margin(1e-12));
    CHECK(run.contact.total_force == Approx(P).epsilon(1e-8));
    CHECK(run.contact.max_pressure == Approx(P / kWidth + 6 * std::abs(M) / (kWidth * kWidth)).epsilon(1e-8));
    const Balance balance = contact_balance(run, Eigen::Vector3d::UnitY(), Eigen::Vector3d(0, kHeight, 0));
    CHECK(balance.moment.z() == Approx(-M).margin(1e-12));  // the base balances the moment on the top
  }
}

TEST_CASE("the moment turns with the scene: the block turned by 30 degrees sinks and turns as upright",
          "[validation][force_control][moment]") {
  // The force's and the moment's components stay along the scene's own axes, as a push's do.
  const RunReport upright = run_patched("scenes/block-moment.json", "{}");
  const RunReport turned = run_patched("scenes/block-moment.json", R"({"transform": {"rotate_degrees": 30}})");
  INFO(turned.result.message);
  REQUIRE(turned.result.status == Status::Converged);
  const Reaction& a = turning_surface_of(upright);
  const Reaction& b = turning_surface_of(turned);
  CHECK(*b.displacement[1] == Approx(*a.displacement[1]).epsilon(1e-8));
  CHECK(*b.rotation[2] == Approx(*a.rotation[2]).epsilon(1e-8));
  CHECK(b.about.isApprox(a.about));  // in the scene's own frame, as the load gives it
  CHECK(turned.contact.max_pressure == Approx(upright.contact.max_pressure).epsilon(1e-8));
}

TEST_CASE("a block tilted on another block: two bodies sink and turn as one block of their height",
          "[validation][force_control][moment][bodies]") {
  // Two identical blocks, the lower one's base on y = 0 (held along y only), the upper one's
  // top carrying the force and the moment; the frictionless interface presses everywhere, so
  // beam theory holds through the stack: the top sinks and turns as a block of height 2H would.
  const Scene scene = parse_scene(R"({"model": "plane_strain",
    "bodies": [
      {"name": "lower", "shape": "rectangle", "width": 2.0, "height": 1.0,
       "mesh": {"size": 0.25, "contact_size": 0.25, "order": 2}, "material": {"E": 1.0, "nu": 0.3},
       "load": {"type": "displacement", "boundary": "bottom", "value": [null, 0.0]}},
      {"name": "upper", "shape": "rectangle", "width": 2.0, "height": 1.0, "offset": [0, 1.0],
       "mesh": {"size": 0.25, "contact_size": 0.25, "order": 2}, "material": {"E": 1.0, "nu": 0.3},
       "load": {"type": "force", "boundary": "top", "value": [null, -0.01], "moment": 0.002}}],
    "contact": [{"pair": ["upper.bottom", "lower.top"]}],
    "solver": {"backend": "active_set", "tol": 1e-10}})");
  const RunReport run = run_scene(scene, RunOptions{});
  INFO(run.result.message);
  REQUIRE(run.result.status == Status::Converged);
  const Reaction& top = turning_surface_of(run);
  CHECK(top.load == "bodies[1].load");
  CHECK(top.about.isApprox(Eigen::Vector3d(0, 2 * kHeight, 0)));
  CHECK(*top.displacement[1] == Approx(-2 * kHeight * 0.01 / (kStiffness * kWidth)).epsilon(1e-8));
  CHECK(*top.rotation[2] == Approx(12 * 2 * kHeight * 0.002 / (kStiffness * std::pow(kWidth, 3))).epsilon(1e-8));
}

TEST_CASE("every backend solves the tilted block alike", "[validation][force_control][moment][cross_backend]") {
  const Scene scene = parse_scene(patched_scene("scenes/block-moment.json", "{}"));
  Model model = build_model(scene);
  const QuadraticProgram qp = assemble_qp(model);
  CHECK(qp.null_space.cols() == 3);  // sideways, down and the turn: only the plane holds the block
  SolveOptions options = scene.solver;
  options.tol = 1e-8;
  const SolveResult reference = solve(qp, options);
  REQUIRE(reference.status == Status::Converged);
  CHECK(every_backend_agrees(qp, options, reference) >= 3);
}

TEST_CASE("a moment beyond the kern lifts the block's heel, and the base still balances it",
          "[validation][force_control][moment]") {
  // M = 0.005 > P W / 6: beam theory would pull at the heel; the plane cannot, so the heel lifts.
  const RunReport run = run_patched("scenes/block-moment.json", R"({"load": {"moment": 0.005}})");
  INFO(run.result.message);
  REQUIRE(run.result.status == Status::Converged);
  CHECK(run.contact.contact_nodes < static_cast<int>(run.model->candidates.size()));
  const Balance balance = contact_balance(run, Eigen::Vector3d::UnitY(), Eigen::Vector3d(0, kHeight, 0));
  CHECK(balance.force.y() == Approx(0.01).epsilon(1e-8));
  CHECK(balance.moment.z() == Approx(-0.005).epsilon(1e-8));
  // It turns further than the whole base would let it.
  CHECK(*turning_surface_of(run).rotation[2] > 12 * kHeight * 0.005 / (kStiffness * std::pow(kWidth, 3)));
}

TEST_CASE("a moment beyond P W / 2 tips the block over its heel: unbounded, naming the turn",
          "[validation][force_control][moment]") {
  // No pressure on the base can balance more than P times half the width: the block tips.
  for (const char* patch : {R"({"load": {"moment": 0.02}})", R"({"load": {"value": [null, 0]}})"}) {
    const RunReport run = run_patched("scenes/block-moment.json", patch);
    INFO(patch << ": " << run.result.message);
    CHECK(run.result.status == Status::Unbounded);
    CHECK_THAT(run.result.message, Catch::StartsWith("unbounded: the body moves freely by rotation about"));
    CHECK(std::isfinite(*turning_surface_of(run).rotation[2]));
  }
}

TEST_CASE("a moment along a load path: the angle grows with it and the last step is the one-shot answer",
          "[validation][force_control][moment][steps]") {
  const RunReport one_shot = run_patched("scenes/block-moment.json", "{}");
  const RunReport path = run_patched("scenes/block-moment.json", R"({"load": {"name": "press"},
        "steps": [{"factors": {"press": 0.5}}, {"factors": {"press": 1}}]})");
  INFO(path.result.message);
  REQUIRE(path.result.status == Status::Converged);
  REQUIRE(path.steps.size() == 2);
  const double angle = *turning_surface_of(one_shot).rotation[2];
  for (std::size_t k = 0; k < 2; ++k) {
    const double factor = k == 0 ? 0.5 : 1.0;
    const Reaction* top = nullptr;
    for (const Reaction& r : path.steps[k].reactions)
      if (r.turns()) top = &r;
    REQUIRE(top != nullptr);
    CHECK(top->moment.z() == Approx(factor * 0.002).epsilon(1e-15));   // the step's share of the moment
    CHECK(*top->rotation[2] == Approx(factor * angle).epsilon(1e-8));  // the whole base presses: linear
  }
}

TEST_CASE("a box tilted about two axes: the contact forces balance the force and the moment",
          "[validation][force_control][moment][3d]") {
  // W × D × H = 2 × 1.5 × 1 on a frictionless plane, P = 0.01 down and M = (0.0005, −0.0008, ·).
  // Quadratic tetrahedra load a face's vertices with no share of a uniform pressure, so the
  // vertices where a linear pressure is low lift slightly: beam theory holds to 1e-3 here,
  // statics exactly.
  const RunReport run = run_patched("scenes/block-moment.json", R"({"model": "solid",
      "body": {"shape": "box", "width": 2.0, "depth": 1.5, "height": 1.0,
               "mesh": {"size": 0.5, "contact_size": 0.5, "order": 2}},
      "load": {"value": [null, null, -0.01], "moment": [0.0005, -0.0008, null]},
      "obstacle": {"point": [0, 0, 0], "normal": [0, 0, 1]}})");
  INFO(run.result.message);
  REQUIRE(run.result.status == Status::Converged);
  const Reaction& top = turning_surface_of(run);
  REQUIRE(top.rotation[0].has_value());
  REQUIRE(top.rotation[1].has_value());
  CHECK_FALSE(top.rotation[2].has_value());  // null: held about z
  const double E = 1, area = 2 * 1.5, Ix = 2 * std::pow(1.5, 3) / 12, Iy = 1.5 * std::pow(2.0, 3) / 12;
  CHECK(*top.displacement[2] == Approx(-0.01 / (E * area)).epsilon(1e-3));
  CHECK(*top.rotation[0] == Approx(0.0005 / (E * Ix)).epsilon(1e-3));
  CHECK(*top.rotation[1] == Approx(-0.0008 / (E * Iy)).epsilon(1e-3));
  const Balance balance = contact_balance(run, Eigen::Vector3d::UnitZ(), top.about);
  CHECK(balance.force.z() == Approx(0.01).epsilon(1e-8));
  CHECK(balance.moment.x() == Approx(-0.0005).epsilon(1e-7));
  CHECK(balance.moment.y() == Approx(0.0008).epsilon(1e-7));
}

TEST_CASE("a moment on a rigid surface: bad input exits 2 with one line naming the field",
          "[validation][force_control][moment][cli][input]") {
  TemporaryDirectory directory;
  const auto refused = [&](const std::string& from, const std::string& patch, const std::string& line) {
    const std::string scene = directory.path("bad.json");
    std::ofstream(scene) << patched_scene(from, patch);
    const CliRun r = run_cli("solve " + scene + " --json " + directory.path("out.json"));
    INFO(patch << "\n" << r.err);
    CHECK(r.exit_status == 2);
    CHECK(r.err == "contactqp: error: " + line + "\n");
    CHECK_FALSE(std::filesystem::exists(directory.path("out.json")));
  };
  const std::string block = "scenes/block-moment.json";
  refused(block, R"({"load": {"moment": [0.002]}})",
          "load.moment = [0.002]: must be a number, the moment about z (0: free to turn)");
  refused(block, R"({"load": {"value": [-0.01, null]}})",
          "load.moment = 0.002: turning \"top\" about z moves it along no component the force ties (its lever arm "
          "is 0); give the force along a component the turn moves");
  refused(block, R"({"load": {"moment": null, "about": [0, 1]}})",
          "load.about is the point a moment is taken about: give \"moment\" too");
  refused("scenes/hertz-force.json", R"({"load": {"moment": 0}})",
          "body.symmetry = true: load has a moment (the rigid surface turns), which is not mirror-symmetric about "
          "x = 0; set \"symmetry\": false");
  refused("scenes/hertz-sphere-force.json", R"({"body": {"symmetry": false}, "load": {"moment": [null, null, null]}})",
          "load.moment = [null, null, null]: give at least one component (0: free to turn about that axis)");
}
