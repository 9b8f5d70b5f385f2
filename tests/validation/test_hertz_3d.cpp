// 3D: Hertz's sphere on a rigid plane and Boussinesq's flat punch against their closed forms,
// a block pressed flat (exact), and the invariances under rotations about any axis and a
// change of units, on every backend.
#include <catch2/catch.hpp>
#include <cmath>

#include "contactqp/certificate.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/post.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

// A coarse quarter hemisphere (about 3e3 DOFs) for the checks that run many solves.
const char* kCoarseSphere = R"({"body": {"mesh": {"contact_size": 0.03, "order": 1}}})";

HertzComparison sphere_hertz_of(const SceneRun& run) {
  const auto hertz = compare_with_hertz(run.model, run.contact);
  REQUIRE(hertz.has_value());
  return *hertz;
}

}  // namespace

TEST_CASE("scenes/hertz-sphere.json matches Hertz's sphere", "[validation][hertz][3d]") {
  const SceneRun run = solve_scene("scenes/hertz-sphere.json");
  REQUIRE(run.result.status == Status::Converged);
  const HertzComparison hertz = sphere_hertz_of(run);
  CHECK(hertz.dim == 3);
  CHECK(hertz.radius == 1.0);
  // The issue's acceptance is 3% / 3% / 6%; the shipped 10-node mesh does much better, and a
  // regression shows.
  CHECK(std::abs(hertz.error_contact_radius) < 0.01);
  CHECK(std::abs(hertz.error_max_pressure) < 0.015);
  CHECK(hertz.error_l2 < 0.03);
  CHECK(hertz.contact_radius == Approx(0.1).epsilon(0.05));  // a/R ≈ 0.1 as the scene promises
  CHECK(run.contact.penetrating_non_candidates == 0);
  // The quarter's force, times four, is what the top pushes with (action and reaction).
  CHECK(-run.reactions.at(0).force.z() == Approx(run.contact.total_force).epsilon(1e-8));
  CHECK(run.reactions.at(0).force.head<2>().norm() <= 1e-12 * run.contact.total_force);
}

TEST_CASE("other radii, materials, pushes and meshes stay within Hertz's 3% in 3D", "[validation][hertz][3d][heavy]") {
  const char* patch = GENERATE(
      R"({"body": {"radius": 2.5, "mesh": {"size": 0.5, "contact_size": 0.035}}, "load": {"value": [null, null, -0.025]}})",
      R"({"material": {"E": 210e9, "nu": 0.2}, "load": {"value": [null, null, -0.006]}, "body": {"mesh": {"contact_size": 0.012}}})",
      R"({"body": {"symmetry": false, "mesh": {"contact_size": 0.02}}, "load": {"value": [0.0, 0.0, -0.01]}})");
  CAPTURE(patch);
  const SceneRun run = solve_scene("scenes/hertz-sphere.json", patch);
  REQUIRE(run.result.status == Status::Converged);
  const HertzComparison hertz = sphere_hertz_of(run);
  CHECK(std::abs(hertz.error_contact_radius) < 0.03);
  CHECK(std::abs(hertz.error_max_pressure) < 0.03);
  CHECK(hertz.error_l2 < 0.06);
}

TEST_CASE("10-node tetrahedra reach a smaller pressure error than 4-node ones with fewer DOFs",
          "[validation][hertz][3d]") {
  const SceneRun linear =
      solve_scene("scenes/hertz-sphere.json", R"({"body": {"mesh": {"contact_size": 0.01, "order": 1}}})");
  const SceneRun quadratic =
      solve_scene("scenes/hertz-sphere.json", R"({"body": {"mesh": {"contact_size": 0.02, "order": 2}}})");
  CAPTURE(linear.qp.n_dofs(), quadratic.qp.n_dofs());
  CHECK(quadratic.qp.n_dofs() < 2 * linear.qp.n_dofs());
  CHECK(sphere_hertz_of(quadratic).error_l2 < 0.75 * sphere_hertz_of(linear).error_l2);
  CHECK(std::abs(sphere_hertz_of(quadratic).error_max_pressure) < std::abs(sphere_hertz_of(linear).error_max_pressure));
}

TEST_CASE("a 3D scene turned about any axis: the same force, a and p0 within 1e-6", "[validation][transform][3d]") {
  const SceneRun base = solve_scene("scenes/hertz-sphere.json", kCoarseSphere);
  const char* turn =
      GENERATE(R"({"axis": [1, 2, 3], "rotate_degrees": 37})", R"({"axis": [0, 1, 0], "rotate_degrees": 90})",
               R"({"axis": [-1, 0.5, 0.2], "rotate_degrees": 151.5})");
  CAPTURE(turn);
  const SceneRun turned =
      solve_scene("scenes/hertz-sphere.json",
                  std::string(R"({"body": {"mesh": {"contact_size": 0.03, "order": 1}}, "transform": )") + turn + "}");
  REQUIRE(turned.result.status == Status::Converged);
  CHECK(relative_error(turned.contact.total_force, base.contact.total_force) < 1e-6);
  CHECK(relative_error(turned.contact.contact_radius, base.contact.contact_radius) < 1e-6);
  CHECK(relative_error(turned.contact.max_pressure, base.contact.max_pressure) < 1e-6);
  // The push is the same force along the turned axis.
  const Eigen::Vector3d axis = turned.model.rotation.col(2);
  CHECK(relative_error(-turned.reactions.at(0).force.dot(axis), -base.reactions.at(0).force.z()) < 1e-6);
}

TEST_CASE("3D units: E × 1e±9 and lengths × 1e±3 give the same scaled answer on every backend",
          "[validation][units][3d][heavy]") {
  const Backend backend = GENERATE(from_range(available_backends()));
  CAPTURE(to_string(backend));
  const std::string solver =
      R"(, "solver": {"backend": ")" + to_string(backend) + R"(", "tol": 1e-10, "max_iterations": 20000})";
  const SceneRun base =
      solve_scene("scenes/hertz-sphere.json",
                  std::string(R"({"body": {"mesh": {"contact_size": 0.03, "order": 1}})") + solver + "}");
  REQUIRE(base.result.status == Status::Converged);
  const double E = GENERATE(1e9, 1e-9);
  const double L = GENERATE(1e3, 1e-3);
  CAPTURE(E, L);
  auto text = [](double x) { return format_value(x); };
  const std::string patch = R"({"material": {"E": )" + text(E) + R"(}, "body": {"radius": )" + text(L) +
                            R"(, "mesh": {"size": )" + text(0.2 * L) + R"(, "contact_size": )" + text(0.03 * L) +
                            R"(, "order": 1}}, "load": {"value": [null, null, )" + text(-0.01 * L) + "]}" + solver +
                            "}";
  const SceneRun scaled = solve_scene("scenes/hertz-sphere.json", patch);
  REQUIRE(scaled.result.status == Status::Converged);
  // Force scales with E L², lengths with L, pressures with E.
  CHECK(relative_error(scaled.contact.total_force, base.contact.total_force * E * L * L) < 1e-6);
  CHECK(relative_error(scaled.contact.contact_radius, base.contact.contact_radius * L) < 1e-6);
  CHECK(relative_error(scaled.contact.max_pressure, base.contact.max_pressure * E) < 1e-6);
}

TEST_CASE("a block pressed flat on a plane in 3D: uniform pressure E δ/H, exact with 4-node tetrahedra",
          "[validation][3d]") {
  // Frictionless contact leaves the block free to widen: uniaxial stress σzz = −E δ/H.
  const std::string scene = R"({"model": "solid", "material": {"E": 2.0, "nu": 0.3},
    "body": {"shape": "box", "width": 1.0, "depth": 0.6, "height": 0.5, "symmetry": true,
             "mesh": {"size": 0.15, "contact_size": 0.15}},
    "load": {"type": "displacement", "boundary": "top", "value": [null, null, -0.01]},
    "obstacle": {"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]},
    "solver": {"backend": "active_set", "tol": 1e-12}})";
  const SceneRun run = solve_scene(parse_scene(scene, source_path("scenes/block.json")));
  REQUIRE(run.result.status == Status::Converged);
  const double pressure = 2.0 * 0.01 / 0.5;
  CHECK(run.contact.total_force == Approx(pressure * 1.0 * 0.6).epsilon(1e-9));
  for (const ContactProfilePoint& point : run.contact.profile) CHECK(point.pressure == Approx(pressure).epsilon(1e-8));
  CHECK(run.contact.contact_area == Approx(0.6).epsilon(1e-9));
}

TEST_CASE("scenes/punch.json: Boussinesq's force within 5% and the pressure's shape", "[validation][boussinesq][3d]") {
  const SceneRun run = solve_scene("scenes/punch.json", R"({"body": {"mesh": {"contact_size": 0.06}}})");
  REQUIRE(run.result.status == Status::Converged);
  const auto punch = compare_with_boussinesq(run.model, run.contact);
  REQUIRE(punch.has_value());
  CHECK(punch->force == Approx(2 * 1.0 * 1.0 / (1 - 0.09) * 0.01));
  CHECK(std::abs(punch->error_force) < 0.05);
  CHECK(punch->shape_error < 0.05);  // p(r)·sqrt(a² − r²) constant for r ≤ 0.8a
  CHECK(!compare_with_hertz(run.model, run.contact).has_value());
}
