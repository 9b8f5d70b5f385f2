// A body that only its contacts hold (docs/extremes.md, "Bodies held only by their contacts"):
// Hertz's half cylinder pressed by a pressure on its flat cut, with nothing prescribed along y.
// The contact carries the load exactly (the free translation's balance), Hertz's b and p0 hold
// as for the push that gives the same force, every backend agrees; pulled away, the run says
// which motion is free.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "contactqp/post.hpp"
#include "contactqp/run.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

constexpr double kPressure = 0.00433656;  // scenes/hertz-pressure.json: P = 2 p R for the whole cylinder

struct PressedRun {
  Model model;
  QuadraticProgram qp;
  SolveResult result;
  ContactSummary contact;
  HertzComparison hertz;
};

PressedRun press(const std::string& patch, Backend backend) {
  PressedRun out;
  const Scene scene = parse_scene(patched_scene("scenes/hertz-pressure.json", patch));
  out.model = build_model(scene);
  out.qp = assemble_qp(out.model);
  SolveOptions options = scene.solver;
  options.backend = backend;
  out.result = solve(out.qp, options);
  out.contact = summarize_contact(out.model, out.qp, out.result.u, out.result.lambda);
  const auto hertz = compare_with_hertz(out.model, out.contact);
  REQUIRE(hertz.has_value());
  out.hertz = *hertz;
  return out;
}

}  // namespace

TEST_CASE("a half cylinder pressed by a pressure alone: the plane carries the load, Hertz holds as for the push",
          "[validation][held_by_contact]") {
  const PressedRun pressed = press("{}", Backend::ActiveSet);
  INFO(pressed.result.message);
  REQUIRE(pressed.result.status == Status::Converged);
  REQUIRE(pressed.qp.null_space.cols() == 1);  // the translation along y; symmetry holds x and the rotation
  CHECK(pressed.result.null_space_dimension == 1);
  // The free translation's balance: the contact force equals the load to the solve's tolerance.
  CHECK(pressed.contact.total_force == Approx(2 * kPressure * 1.0).epsilon(1e-7));
  CHECK(pressed.result.diagnostics.at("rigid_balance") < 1e-7);
  // Hertz's b and p0 for that force, within the bounds scenes/hertz.json meets for its push.
  CHECK(std::abs(pressed.hertz.error_half_width) < 0.01);
  CHECK(std::abs(pressed.hertz.error_max_pressure) < 0.015);
  CHECK(pressed.hertz.error_l2 < 0.025);

  // The push of hertz.json gives this force on the same mesh (the scene's pressure is chosen so);
  // a uniform pressure on the cut and a rigid push of it load the half cylinder differently far
  // from the contact, alike near it (Saint-Venant): b and p0 agree to 1% (measured 0.44%).
  const SceneRun pushed = solve_scene("scenes/hertz.json", R"({"solver": {"backend": "active_set"}})");
  CHECK(pushed.contact.total_force == Approx(pressed.contact.total_force).epsilon(1e-6));
  CHECK(pressed.contact.half_width == Approx(pushed.contact.half_width).epsilon(0.01));
  CHECK(pressed.contact.max_pressure == Approx(pushed.contact.max_pressure).epsilon(0.01));
}

TEST_CASE("every backend solves the half cylinder held by the plane alike",
          "[validation][held_by_contact][cross_backend]") {
  // A coarser mesh keeps the dual backends quick.
  const std::string coarse = R"({"body": {"mesh": {"size": 0.2, "contact_size": 0.01}}})";
  const PressedRun reference = press(coarse, Backend::ActiveSet);
  REQUIRE(reference.result.status == Status::Converged);
  int solved = 0;
  for (const Backend backend : available_backends(reference.qp)) {
    const PressedRun run = press(coarse, backend);
    INFO(to_string(backend) << ": " << run.result.message);
    CHECK(run.result.status == Status::Converged);
    if (run.result.status != Status::Converged) continue;
    ++solved;
    const double u_scale = reference.result.u.cwiseAbs().maxCoeff();
    const double lambda_scale = reference.result.lambda.cwiseAbs().maxCoeff();
    CHECK((run.result.u - reference.result.u).cwiseAbs().maxCoeff() <= 1e-6 * u_scale);
    CHECK((run.result.lambda - reference.result.lambda).cwiseAbs().maxCoeff() <= 1e-5 * lambda_scale);
  }
  CHECK(solved >= 3);
}

TEST_CASE("a half cylinder pulled off the plane is unbounded, and the run names the free motion",
          "[validation][held_by_contact]") {
  RunOptions options;
  const RunReport report =
      run_scene(parse_scene(patched_scene("scenes/hertz-pressure.json", R"({"load": {"value": -0.001}})")), options);
  INFO(report.result.message);
  CHECK(report.result.status == Status::Unbounded);
  CHECK_THAT(report.result.message, Catch::StartsWith("unbounded: the body moves freely along +y: the load pushes it "
                                                      "away from every contact"));
  CHECK(report.result.u.cwiseAbs().maxCoeff() == 0);
}

TEST_CASE("the whole half disc pushed down is solved with its sideways translation free and undriven",
          "[validation][held_by_contact]") {
  // No symmetry plane: u_x is prescribed nowhere, and neither the push nor the plane acts along x.
  const SceneRun run =
      solve_scene("scenes/hertz.json", R"({"body": {"symmetry": false}, "solver": {"backend": "active_set"}})");
  INFO(run.result.message);
  REQUIRE(run.result.status == Status::Converged);
  CHECK(run.result.null_space_dimension == 1);
  CHECK(run.result.diagnostics.at("undriven_modes") == 1);
  // The stated choice: the smallest norm along x, so no net sideways shift of the body.
  CHECK(run.contact.total_force == Approx(0.008657).epsilon(0.01));
  CHECK(run.contact.centre == Approx(0.0).margin(1e-3));
}

TEST_CASE("Hertz's half ball pressed by a pressure alone: the plane carries the load, Hertz's a and p0 hold",
          "[validation][held_by_contact][3d][heavy]") {
  const SceneRun run = solve_scene("scenes/hertz-sphere-pressure.json");
  INFO(run.result.message);
  REQUIRE(run.result.status == Status::Converged);
  CHECK(run.qp.null_space.cols() == 1);  // the translation along z; the symmetry planes hold the rest
  // The plane carries the load: p times the meshed top's area (π R² but for the mesh's chords on
  // the rim, 3e-6 less here), for the whole ball (× 4 the quarter modelled).
  double applied = 0;
  for (int node = 0; node < run.model.mesh.n_nodes(); ++node) applied -= 4 * run.model.nodal_force[3 * node + 2];
  CHECK(run.contact.total_force == Approx(applied).epsilon(1e-7));
  CHECK(applied == Approx(M_PI * 0.000493011084).epsilon(1e-5));
  const auto hertz = compare_with_hertz(run.model, run.contact);
  REQUIRE(hertz.has_value());
  // Within the bounds scenes/hertz-sphere.json meets for its push (which gives this force).
  CHECK(std::abs(hertz->error_contact_radius) < 0.01);
  CHECK(std::abs(hertz->error_max_pressure) < 0.015);
}

TEST_CASE("the CLI ends a body pulled off its only contact with exit 1 and the line that names the motion",
          "[validation][held_by_contact][cli]") {
  TemporaryDirectory directory;
  const std::string scene = directory.path("pulled.json");
  std::ofstream(scene) << patched_scene("scenes/hertz-pressure.json", R"({"load": {"value": -0.001}})");
  const CliRun r = run_cli("solve " + scene + " --json " + directory.path("out.json"));
  CHECK(r.exit_status == 1);
  CHECK(r.out.find("unbounded: the body moves freely along +y") != std::string::npos);
  const nlohmann::json result = nlohmann::json::parse(std::ifstream(directory.path("out.json")));
  CHECK(result["status"] == "unbounded");
  CHECK(result["recession"]["motion"] == "along +y");
  CHECK(result["recession"]["f_dot_d"].get<double>() > 0);
  CHECK(result["recession"]["max_B_d"].get<double>() <= 1e-12);
  CHECK(result["recession"]["max_abs_K_d"].get<double>() <= 1e-9);
}

TEST_CASE("a cylinder pressed by a pressure onto another: the pair carries the load, Hertz for two cylinders holds",
          "[validation][held_by_contact][bodies]") {
  const RunReport pressed = run_scene(load_scene(source_path("scenes/two-cylinders-pressure.json")), RunOptions{});
  INFO(pressed.result.message);
  REQUIRE(pressed.result.status == Status::Converged);
  CHECK(pressed.qp->null_space.cols() == 1);  // the roller's translation along y
  REQUIRE(pressed.pairs.size() == 1);
  // The pair carries the roller's load: 2 p R1 for the whole roller, action and reaction.
  CHECK(pressed.pairs[0].force_on_node_body.y() == Approx(2 * 0.002469495).epsilon(1e-7));
  REQUIRE(pressed.pairs[0].hertz.has_value());
  CHECK(std::abs(pressed.pairs[0].hertz->error_half_width) < 0.01);
  CHECK(std::abs(pressed.pairs[0].hertz->error_max_pressure) < 0.01);
  // The push of two-cylinders.json gives this force on the same mesh: b and p0 agree to 1%.
  const RunReport pushed = run_scene(load_scene(source_path("scenes/two-cylinders.json")), RunOptions{});
  REQUIRE(pushed.pairs.size() == 1);
  CHECK(pushed.pairs[0].force_on_node_body.y() == Approx(pressed.pairs[0].force_on_node_body.y()).epsilon(1e-6));
  CHECK(pressed.pairs[0].half_width == Approx(pushed.pairs[0].half_width).epsilon(0.01));
  CHECK(pressed.pairs[0].max_pressure == Approx(pushed.pairs[0].max_pressure).epsilon(0.01));
}
