// The shipped scenes beyond the half disc, against what is known independently: Hertz's
// solution for each cylinder contact, equilibrium with the applied loads, symmetry, the
// homogeneity of a receding contact, and the equivalence of one V profile and two planes.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

HertzComparison hertz_of(const SceneRun& run, int obstacle = 0) {
  const auto hertz = compare_with_hertz(run.model, run.contact.obstacles.at(obstacle));
  REQUIRE(hertz.has_value());
  return *hertz;
}

// Nodes carrying contact force (λ > 1e-8 max λ).
std::set<int> loaded_nodes(const SceneRun& run) {
  std::set<int> nodes;
  const double largest = run.result.lambda.maxCoeff();
  for (int i = 0; i < run.qp.n_constraints(); ++i)
    if (run.result.lambda[i] > 1e-8 * largest) nodes.insert(run.model.candidates[i].node);
  return nodes;
}

}  // namespace

TEST_CASE("the Gmsh-meshed Hertz disc passes the 3% Hertz check", "[validation][scenes][gmsh]") {
  const SceneRun run = solve_scene("scenes/hertz-gmsh.json");
  REQUIRE(run.result.status == Status::Converged);
  const HertzComparison hertz = hertz_of(run);
  CHECK(hertz.radius_source == "fitted");
  CHECK(hertz.radius == Approx(1.0).epsilon(1e-3));  // the nodes in contact lie on the unit circle
  CHECK(std::abs(hertz.error_half_width) < 0.03);
  CHECK(std::abs(hertz.error_max_pressure) < 0.03);
  CHECK(hertz.error_l2 < 0.05);
  CHECK(run.contact.penetrating_non_candidates == 0);
  // The cut pushes with the contact force: the only other external force.
  CHECK(-run.reactions.at(0).force.y() == Approx(run.contact.total_force).epsilon(1e-6));
}

TEST_CASE("a rigid circle pressed into a flat block matches Hertz with R = r within 5%", "[validation][scenes]") {
  const char* patch =
      GENERATE(R"({})", R"({"obstacle": {"center": [0, -2.5], "radius": 2.5}, "load": {"value": [null, -0.03]}})",
               R"({"material": {"E": 70e9, "nu": 0.33}, "body": {"width": 6, "height": 3}})");
  CAPTURE(patch);
  const SceneRun run = solve_scene("scenes/block-on-circle.json", patch);
  REQUIRE(run.result.status == Status::Converged);
  const HertzComparison hertz = hertz_of(run);
  CHECK(hertz.radius_source == "obstacle.radius");
  CHECK(hertz.radius == run.model.scene.obstacles[0].as<CircleObstacle>()->radius);
  CHECK(std::abs(hertz.error_half_width) < 0.05);
  CHECK(std::abs(hertz.error_max_pressure) < 0.05);
  CHECK(hertz.error_l2 < 0.05);
}

TEST_CASE("a circle into a Gmsh-meshed flat block, turned: the fitted body curvature is zero",
          "[validation][scenes][gmsh]") {
  TemporaryDirectory directory;
  std::ofstream(directory.path("block.geo")) << R"geo(
Point(1) = {-2, 0, 0}; Point(2) = {2, 0, 0}; Point(3) = {2, 2, 0}; Point(4) = {-2, 2, 0};
Point(5) = {-0.15, 0, 0}; Point(6) = {0.15, 0, 0};
Line(1) = {1, 5}; Line(2) = {5, 6}; Line(3) = {6, 2}; Line(4) = {2, 3}; Line(5) = {3, 4}; Line(6) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6}; Plane Surface(1) = {1};
Physical Curve("bottom") = {1, 2, 3}; Physical Curve("top") = {5}; Physical Surface("block") = {1};
Field[1] = Distance; Field[1].CurvesList = {2}; Field[1].NumPointsPerCurve = 300;
Field[2] = MathEval; Field[2].F = "Min(0.2, 0.003 + 0.1 * F1)"; Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
)geo";
  const std::string msh = directory.path("block.msh");
  REQUIRE(std::system(
              ("gmsh " + directory.path("block.geo") + " -2 -format msh22 -o " + msh + " >/dev/null 2>&1").c_str()) ==
          0);
  const SceneRun run = solve_scene(parse_scene(R"({"material": {"E": 200e9, "nu": 0.3},
      "body": {"shape": "mesh", "file": ")" + msh +
                                               R"("},
      "load": {"type": "displacement", "boundary": "top", "value": [0, -0.02]},
      "obstacle": {"type": "circle", "center": [0, -1], "radius": 1},
      "contact": {"boundary": "bottom"}, "transform": {"rotate_degrees": 77}})"));
  REQUIRE(run.result.status == Status::Converged);
  const HertzComparison hertz = hertz_of(run);
  CHECK(hertz.radius_source == "fitted and obstacle.radius");
  CHECK(hertz.radius == Approx(1.0).epsilon(1e-9));
  CHECK(std::abs(hertz.error_half_width) < 0.05);
  CHECK(std::abs(hertz.error_max_pressure) < 0.05);
}

TEST_CASE("a disc in a V-groove: two Hertz contacts in equilibrium with the push", "[validation][scenes]") {
  const SceneRun run = solve_scene("scenes/disc-in-vgroove.json");
  REQUIRE(run.result.status == Status::Converged);
  REQUIRE(run.contact.obstacles.size() == 2);
  const ObstacleContact& left = run.contact.obstacles[0];
  const ObstacleContact& right = run.contact.obstacles[1];
  CHECK(left.total_force == Approx(right.total_force).epsilon(1e-3));  // a symmetric scene on an unstructured mesh
  for (int o = 0; o < 2; ++o) {
    CAPTURE(o);
    const HertzComparison hertz = hertz_of(run, o);
    CHECK(hertz.radius == 1.0);
    CHECK(std::abs(hertz.error_half_width) < 0.03);
    CHECK(std::abs(hertz.error_max_pressure) < 0.03);
  }
  // Each wall pushes along its normal at 45°: their vertical parts carry the push.
  const Eigen::Vector2d push = run.reactions.at(0).force.head<2>();
  CHECK(-push.y() == Approx((left.total_force + right.total_force) / std::sqrt(2.0)).epsilon(1e-6));
  CHECK(push.x() == Approx((right.total_force - left.total_force) / std::sqrt(2.0)).margin(1e-6 * std::abs(push.y())));
  CHECK(!compare_with_hertz(run.model, run.contact).has_value());  // one Hertz zone per wall, not one overall
}

TEST_CASE("one V-shaped profile acts as two planes", "[validation][scenes][profile]") {
  const std::string coarse = R"({"body": {"mesh": {"contact_size": 0.01}}})";
  const SceneRun planes = solve_scene("scenes/disc-in-vgroove.json", coarse);
  const SceneRun profile = solve_scene("scenes/disc-in-vgroove.json", R"({"body": {"mesh": {"contact_size": 0.01}},
      "obstacle": {"type": "profile", "points": [[-1.5, 1.0857864376269049], [0, -0.41421356237309503], [1.5, 1.0857864376269049]],
                   "body_side": "left"}})");
  REQUIRE(planes.result.status == Status::Converged);
  REQUIRE(profile.result.status == Status::Converged);
  CHECK(profile.model.mesh.n_nodes() == planes.model.mesh.n_nodes());
  CHECK(profile.qp.n_constraints() == planes.qp.n_constraints());
  CHECK(profile.contact.total_force == Approx(planes.contact.total_force).epsilon(1e-6));
  CHECK(profile.contact.max_pressure == Approx(planes.contact.max_pressure).epsilon(1e-6));
  CHECK(loaded_nodes(profile) == loaded_nodes(planes));
}

TEST_CASE("a strip lifts off its foundation beyond a receding contact zone", "[validation][scenes][liftoff]") {
  const SceneRun run = solve_scene("scenes/strip-liftoff.json");
  REQUIRE(run.result.status == Status::Converged);
  const Eigen::VectorXd u = full_displacement(run.model, run.result.u);
  double inner_gap = 0, end_gap = 0, widest = 0;
  for (int node : loaded_nodes(run)) widest = std::max(widest, std::abs(run.model.mesh.nodes[node].x()));
  for (int node : boundary_nodes(run.model.mesh, "bottom")) {
    const double x = run.model.mesh.nodes[node].x(), gap = u[2 * node + 1];  // the foundation is y = 0
    if (std::abs(x) < 1.0) inner_gap = std::max(inner_gap, gap);
    if (std::abs(x) > 1.9) end_gap = std::max(end_gap, gap);
  }
  CHECK(widest < 1.6);  // contact under the middle only ...
  CHECK(widest > 0.9);
  CHECK(inner_gap < 1e-6 * 0.01);  // ... closed there (the punch pushes 0.01) ...
  CHECK(end_gap > 1e-4);           // ... and the ends off the ground
  // Vertical equilibrium: the foundation carries the punch and the strip's weight.
  const double weight = 0.05 * 9.81 * 4.0 * 1.0;
  CHECK(run.contact.total_force == Approx(-run.reactions.at(0).force.y() + weight).epsilon(1e-6));
}

TEST_CASE("without weight the contact zone does not depend on the push", "[validation][scenes][liftoff]") {
  // The strip touches its foundation with zero gap: the problem is positively homogeneous, so
  // ten times the push gives ten times every force on the same contact zone.
  const std::string weightless = R"({"load": [{"type": "displacement", "boundary": "punch", "value": [0.0, -0.01]}]})";
  const SceneRun push = solve_scene("scenes/strip-liftoff.json", weightless);
  const SceneRun harder =
      solve_scene("scenes/strip-liftoff.json",
                  R"({"load": [{"type": "displacement", "boundary": "punch", "value": [0.0, -0.1]}]})");
  REQUIRE(push.result.status == Status::Converged);
  REQUIRE(harder.result.status == Status::Converged);
  CHECK(loaded_nodes(push) == loaded_nodes(harder));
  CHECK(harder.contact.total_force == Approx(10 * push.contact.total_force).epsilon(1e-6));
  CHECK(harder.contact.half_width == Approx(push.contact.half_width).epsilon(1e-6));
}

TEST_CASE("6-node triangles reach the 3-node accuracy with a quarter of the DOFs", "[validation][scenes][order]") {
  const SceneRun linear = solve_scene("scenes/hertz.json");
  const SceneRun quadratic = solve_scene("scenes/hertz-order2.json");
  REQUIRE(quadratic.result.status == Status::Converged);
  CHECK(4 * quadratic.qp.n_dofs() <= linear.qp.n_dofs());
  const HertzComparison h1 = hertz_of(linear), h2 = hertz_of(quadratic);
  CHECK(h2.error_l2 <= h1.error_l2);
  CHECK(std::abs(h2.error_max_pressure) <= std::abs(h1.error_max_pressure));
  // The force against the independent reference P ≈ 0.008657 (docs/architecture.md).
  CHECK(std::abs(quadratic.contact.total_force / 0.008657 - 1) <= std::abs(linear.contact.total_force / 0.008657 - 1));
  // The paper's remark: with quadratic shape functions contact is imposed at the vertices and
  // at the mid-side nodes; both carry force.
  std::set<int> mid_sides;
  for (const BoundaryFace& edge : quadratic.model.mesh.boundaries.at("arc")) mid_sides.insert(edge.nodes[2]);
  int loaded_mid = 0, loaded_vertex = 0;
  for (int node : loaded_nodes(quadratic)) (mid_sides.count(node) ? loaded_mid : loaded_vertex)++;
  CHECK(loaded_mid >= 5);
  CHECK(loaded_vertex >= 5);
}

TEST_CASE("plane stress with a thickness: forces scale with it, pressures do not", "[validation][scenes]") {
  const std::string base =
      R"({"model": "plane_stress", "body": {"mesh": {"size": 0.4, "contact_size": 0.01}}, "contact": {"max_gap": 0.05},
      "load": [{"type": "displacement", "boundary": "top", "value": [null, -0.02]}, {"type": "gravity", "density": 0.001, "g": [0, -1]},
               {"type": "traction", "boundary": "right", "value": [0, -0.001]}]})";
  const SceneRun unit = solve_scene("scenes/block-on-circle.json", base);
  nlohmann::json thin = nlohmann::json::parse(patched_scene("scenes/block-on-circle.json", base));
  thin["body"]["thickness"] = 0.25;
  const SceneRun quarter = solve_scene(parse_scene(thin.dump(), source_path("scenes/x.json")));
  CHECK(quarter.contact.total_force == Approx(0.25 * unit.contact.total_force).epsilon(1e-6));
  CHECK(quarter.contact.max_pressure == Approx(unit.contact.max_pressure).epsilon(1e-6));
  CHECK(quarter.contact.half_width == Approx(unit.contact.half_width).epsilon(1e-6));
  const HertzComparison hertz = hertz_of(quarter);
  CHECK(hertz.effective_modulus == 1.0);  // E* = E in plane stress
  CHECK(std::abs(hertz.error_half_width) < 0.05);
}
