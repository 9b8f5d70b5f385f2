// A ball between two plates, pressed by a force (scenes/ball-between-plates.json): one body that
// only its two contacts hold. The independent truths: equilibrium (each contact carries the
// plate's force P), Hertz's b and p0 at each contact (a cylinder on a flat: R the ball's, fitted
// from the mesh), the mirror symmetry about the ball's centre (identical plates, one held at its
// bottom, the other's top moved by d: the ball moves by d/2), and the displacement-driven twin.
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>

#include "contactqp/post.hpp"
#include "contactqp/run.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

const char* const kBallScene = "scenes/ball-between-plates.json";

RunReport run_ball_patched(const std::string& patch) {
  return run_scene(parse_scene(patched_scene(kBallScene, patch)), RunOptions{});
}

// The upper plate's top as the scene has it, with its load replaced.
std::string upper_plate_with(const std::string& load) {
  return R"({"name": "upper_plate", "shape": "rectangle", "width": 1.2, "height": 0.4, "offset": [0, 2.0],
             "symmetry": true, "mesh": {"size": 0.05, "contact_size": 0.002},
             "material": {"E": 2.0, "nu": 0.25}, "load": )" +
         load + "}";
}

std::string ball_and_lower_plate(const std::string& ball_material) {
  return R"({"name": "ball", "shape": "mesh", "file": ")" + source_path("scenes/ball.geo") +
         R"(", "symmetry": true, "material": )" + ball_material +
         R"(}, {"name": "lower_plate", "shape": "rectangle", "width": 1.2, "height": 0.4, "offset": [0, -0.4],
             "symmetry": true, "mesh": {"size": 0.05, "contact_size": 0.002},
             "material": {"E": 2.0, "nu": 0.25},
             "load": {"type": "displacement", "boundary": "bottom", "value": [null, 0.0]}})";
}

const FloatingBody& floating_body_named(const RunReport& report, const std::string& name) {
  for (const FloatingBody& body : report.floating)
    if (body.body == name) return body;
  FAIL("no floating body " << name);
  return report.floating.front();
}

double plate_move(const RunReport& report) {
  for (const Reaction& r : report.reactions)
    if (r.rigid_surface()) return *r.displacement[1];
  FAIL("no rigid surface");
  return 0;
}

// Every check of the scene for a force P and the ball's modulus: equilibrium at each contact to
// 1e-8, Hertz at each within `hertz_tolerance` (the mesh's), the fitted radius to 1e-6, the ball
// moved by half the plate.
void check_ball_between_plates(const RunReport& report, double P, double hertz_tolerance) {
  INFO(report.result.message);
  REQUIRE(report.result.status == Status::Converged);
  REQUIRE(report.pairs.size() == 2);
  for (const PairContact& pair : report.pairs) {
    INFO(pair.node_side);
    CHECK(std::abs(pair.force_on_node_body.y()) == Approx(P).epsilon(1e-8));
    CHECK(std::abs(pair.force_on_node_body.x()) < 1e-12 * P);
    REQUIRE(pair.hertz);
    CHECK(pair.hertz->radius == Approx(1.0).epsilon(1e-6));  // fitted through the ball's nodes
    CHECK(pair.hertz->force == Approx(P).epsilon(1e-8));
    CHECK(std::abs(pair.hertz->error_half_width) < hertz_tolerance);
    CHECK(std::abs(pair.hertz->error_max_pressure) < hertz_tolerance);
  }
  // The pressures push the ball up from below and down from above.
  CHECK(report.pairs[0].force_on_node_body.y() > 0);
  CHECK(report.pairs[1].force_on_node_body.y() < 0);
  const FloatingBody& ball = floating_body_named(report, "ball");
  CHECK_FALSE(ball.translation[0]);  // the symmetry plane holds it along x
  REQUIRE(ball.translation[1]);
  const double d = plate_move(report);
  CHECK(d < 0);
  CHECK(*ball.translation[1] == Approx(d / 2).epsilon(2e-3));  // the meshes are not exact mirror images
}

}  // namespace

TEST_CASE("a ball between two plates pressed by a force: each contact carries P, Hertz at each",
          "[validation][force_control][bodies]") {
  const RunReport report = run_scene(load_scene(source_path(kBallScene)), RunOptions{});
  check_ball_between_plates(report, 0.005, 0.012);
  // Hertz's b for a cylinder of radius 1 on a flat, 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2.
  const double E_star = 1.0 / ((1 - 0.09) / 1.0 + (1 - 0.0625) / 2.0);
  const double P = report.pairs[0].hertz->force;
  CHECK(report.pairs[0].hertz->half_width == Approx(std::sqrt(4 * P / (M_PI * E_star))).epsilon(1e-12));
  // Two free modes: the ball's and the upper plate's translations along y.
  CHECK(report.floating.size() == 2);
  CHECK(floating_body_named(report, "upper_plate").translation[1]);
}

TEST_CASE("a ball between two plates: another force and another ball material", "[validation][force_control][bodies]") {
  const double P = 0.002;
  const RunReport report = run_ball_patched(
      R"({"bodies": [)" + ball_and_lower_plate(R"({"E": 1.5, "nu": 0.2})") + ", " +
      upper_plate_with(R"({"type": "force", "boundary": "top", "value": [null, -)" + nlohmann::json(P).dump() + "]}") +
      "]}");
  check_ball_between_plates(report, P, 0.02);
  const double E_star = 1.0 / ((1 - 0.04) / 1.5 + (1 - 0.0625) / 2.0);
  CHECK(report.pairs[1].hertz->effective_modulus == Approx(E_star).epsilon(1e-12));
}

TEST_CASE("a ball between two plates: the push that moves the plate as the force did gives that force",
          "[validation][force_control][bodies]") {
  const RunReport forced = run_scene(load_scene(source_path(kBallScene)), RunOptions{});
  REQUIRE(forced.result.status == Status::Converged);
  const double d = plate_move(forced);
  const RunReport pushed =
      run_ball_patched(R"({"bodies": [)" + ball_and_lower_plate(R"({"E": 1.0, "nu": 0.3})") + ", " +
                       upper_plate_with(R"({"type": "displacement", "boundary": "top", "value": [null, )" +
                                        nlohmann::json(d).dump() + "]}") +
                       "]}");
  INFO(pushed.result.message);
  REQUIRE(pushed.result.status == Status::Converged);
  for (int k = 0; k < 2; ++k)
    CHECK(pushed.pairs[k].force_on_node_body.y() == Approx(forced.pairs[k].force_on_node_body.y()).epsilon(1e-6));
  // The ball still floats: its translation as the force-driven run has it.
  CHECK(*floating_body_named(pushed, "ball").translation[1] ==
        Approx(*floating_body_named(forced, "ball").translation[1]).epsilon(1e-6));
}

TEST_CASE("a ball between two plates, the upper plate pulled away: unbounded, naming the plate",
          "[validation][force_control][bodies]") {
  const RunReport pulled =
      run_ball_patched(R"({"bodies": [)" + ball_and_lower_plate(R"({"E": 1.0, "nu": 0.3})") + ", " +
                       upper_plate_with(R"({"type": "force", "boundary": "top", "value": [null, 0.005]})") + "]}");
  CHECK(pulled.result.status == Status::Unbounded);
  CHECK_THAT(pulled.result.message, Catch::StartsWith("unbounded: body `upper_plate` moves freely along +y"));
  CHECK(pulled.floating.empty());
}
