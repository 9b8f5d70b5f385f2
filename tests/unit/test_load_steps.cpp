// Load steps (docs/friction.md): the factors of each step, and a step's f and g equal to those of
// the scene with its loads scaled so; with no friction, steps end where one solve does.
#include <catch2/catch.hpp>

#include "contactqp/model.hpp"
#include "contactqp/run.hpp"
#include "contactqp/scene.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

TEST_CASE("a step's factors: totals for the loads it names, the last ones for the others", "[unit][steps]") {
  const Scene scene = parse_scene(patched_scene("scenes/hertz.json", R"({"load": [
      {"name": "a", "type": "displacement", "boundary": "top", "value": [null, -0.016]},
      {"name": "b", "type": "gravity", "density": 1, "g": [0, -1]},
      {"type": "gravity", "density": 2, "g": [0, -1]}],
      "steps": [{"factors": {"a": 1}}, {"factors": {"b": 0.5}}, {"factors": {"a": 0.2, "b": 0}}]})"));
  const std::vector<std::vector<double>> factors = load_factors(scene);
  REQUIRE(factors.size() == 3);
  CHECK(factors[0] == std::vector<double>{1, 0, 1});  // b waits for its first step; the unnamed load is always in
  CHECK(factors[1] == std::vector<double>{1, 0.5, 1});
  CHECK(factors[2] == std::vector<double>{0.2, 0, 1});
  CHECK(load_factors(parse_scene(read_text(source_path("scenes/hertz.json")))) ==
        std::vector<std::vector<double>>{{1}});
}

TEST_CASE("a step's f and g are those of the scene with its loads scaled", "[unit][steps]") {
  const std::string named = R"({"load": [
      {"name": "push", "type": "displacement", "boundary": "top", "value": [null, -0.016]},
      {"name": "weight", "type": "gravity", "density": 0.01, "g": [0, -1]}],
      "steps": [{"factors": {"push": 0.25, "weight": 3}}]})";
  Model model = build_model(parse_scene(patched_scene("scenes/hertz.json", named)));
  QuadraticProgram qp = assemble_qp(model);
  apply_load_step(model, qp, load_factors(model.scene).front(), "steps[0]");
  Model scaled = build_model(parse_scene(patched_scene("scenes/hertz.json", R"({"load": [
      {"type": "displacement", "boundary": "top", "value": [null, -0.004]},
      {"type": "gravity", "density": 0.03, "g": [0, -1]}]})")));
  const QuadraticProgram expected = assemble_qp(scaled);
  REQUIRE(qp.n_dofs() == expected.n_dofs());
  CHECK(relative_difference(qp.f, expected.f) < 1e-13);
  CHECK(relative_difference(qp.g, expected.g) < 1e-13);
  CHECK(relative_difference(model.prescribed, scaled.prescribed) < 1e-15);
  CHECK(relative_difference(model.nodal_force, scaled.nodal_force) < 1e-13);
  CHECK(SparseMatrix(qp.K - expected.K).norm() == 0);
}

TEST_CASE("frictionless steps end where one solve of the whole load does", "[unit][steps]") {
  Scene scene = parse_scene(patched_scene("scenes/hertz.json", R"({
      "load": {"name": "push", "type": "displacement", "boundary": "top", "value": [null, -0.016]},
      "steps": [{"factors": {"push": 0.25}}, {"factors": {"push": 0.5}}, {"factors": {"push": 1}}],
      "solver": {"backend": "active_set", "tol": 1e-10}})"));
  const RunReport stepped = contactqp::run_scene(scene, RunOptions{});
  Scene whole = parse_scene(read_text(source_path("scenes/hertz.json")));
  whole.solver = scene.solver;
  const RunReport once = contactqp::run_scene(whole, RunOptions{});
  REQUIRE(stepped.steps.size() == 3);
  for (const StepReport& step : stepped.steps) CHECK(step.status == Status::Converged);
  CHECK(relative_difference(stepped.result.u, once.result.u) < 1e-10);
  CHECK(relative_difference(stepped.result.lambda, once.result.lambda) < 1e-10);
  // The P–δ curve rises faster than linearly (the zone grows): P(δ/4) < P(δ)/4.
  const double P1 = stepped.steps[0].contact.total_force, P3 = stepped.steps[2].contact.total_force;
  CHECK(P3 == Approx(once.contact.total_force).epsilon(1e-10));
  CHECK(P1 < P3 / 4);
  CHECK(stepped.steps[0].contact.half_width < stepped.steps[2].contact.half_width);
}
