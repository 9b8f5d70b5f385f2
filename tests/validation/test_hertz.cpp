// Hertz's cylinder on a rigid plane: the computed contact against the analytic solution, and
// the invariances under a change of units.
#include <catch2/catch.hpp>

#include "contactqp/certificate.hpp"
#include "contactqp/post.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

struct HertzRun {
  SolveResult result;
  Certificate certificate;
  ContactSummary contact;
  HertzComparison hertz;
};

HertzRun run(const Scene& scene) {
  Model model = build_model(scene);
  const QuadraticProgram qp = assemble_qp(model);
  HertzRun out;
  out.result = solve(qp, scene.solver);
  out.certificate = certify(qp, out.result.u, out.result.lambda, out.result.K_factor.get());
  out.contact = summarize_contact(model, qp, out.result.u, out.result.lambda);
  const auto hertz = compare_with_hertz(model, out.contact);
  REQUIRE(hertz.has_value());
  out.hertz = *hertz;
  return out;
}

Scene hertz_scene(const std::string& patch = "{}") { return parse_scene(patched_scene("scenes/hertz.json", patch)); }

}  // namespace

TEST_CASE("scenes/hertz.json matches Hertz and the independent reference force", "[validation][hertz]") {
  const HertzRun r = run(load_scene(source_path("scenes/hertz.json")));
  REQUIRE(r.result.status == Status::Converged);
  CHECK(r.certificate.kkt_max() < 1e-7);
  CHECK(std::abs(r.certificate.relative_gap) < 1e-8);
  // docs/architecture.md: an independent FE code gives P ≈ 0.008657 E R on this geometry; a
  // mesh graded this coarsely away from the contact stays within 1% of it.
  CHECK(r.contact.total_force == Approx(0.008657).epsilon(0.01));
  // The issue's acceptance is 3% / 3% / 5%; this mesh does better, and a regression shows.
  CHECK(std::abs(r.hertz.error_half_width) < 0.01);
  CHECK(std::abs(r.hertz.error_max_pressure) < 0.015);
  CHECK(r.hertz.error_l2 < 0.025);
  CHECK(r.contact.half_width / 1.0 == Approx(0.1).epsilon(0.03));  // b/R ≈ 0.1 as the scene promises
  CHECK(r.contact.penetrating_non_candidates == 0);
}

TEST_CASE("other radii, materials, loads and meshes stay within Hertz's 3%", "[validation][hertz]") {
  const char* patch = GENERATE(
      R"({"body": {"radius": 2.5, "mesh": {"size": 0.25, "contact_size": 0.005}}, "load": {"value": [null, -0.04]}})",
      R"({"material": {"E": 210e9, "nu": 0.2}, "load": {"value": [null, -0.008]}, "body": {"mesh": {"contact_size": 0.0015}}})",
      R"({"model": "plane_stress", "material": {"nu": 0.45}, "body": {"mesh": {"order": 2, "contact_size": 0.004}}})",
      R"({"body": {"symmetry": false}, "load": {"value": [0.0, -0.016]}})");
  CAPTURE(patch);
  const HertzRun r = run(hertz_scene(patch));
  REQUIRE(r.result.status == Status::Converged);
  CHECK(std::abs(r.hertz.error_half_width) < 0.03);
  CHECK(std::abs(r.hertz.error_max_pressure) < 0.03);
  CHECK(r.hertz.error_l2 < 0.05);
}

TEST_CASE("units: E × 1e9 scales pressures, lengths × 1e-3 scale b", "[validation][hertz][units]") {
  const HertzRun base = run(hertz_scene());
  SECTION("E × 1e9, δ unchanged") {
    const HertzRun stiff = run(hertz_scene(R"({"material": {"E": 1e9}})"));
    REQUIRE(stiff.result.status == Status::Converged);
    CHECK(stiff.contact.half_width == Approx(base.contact.half_width).epsilon(1e-6));
    CHECK(stiff.contact.max_pressure == Approx(1e9 * base.contact.max_pressure).epsilon(1e-6));
    CHECK(stiff.contact.total_force == Approx(1e9 * base.contact.total_force).epsilon(1e-6));
  }
  SECTION("lengths × 1e-3, E unchanged") {
    const HertzRun small = run(hertz_scene(R"({"body": {"radius": 1e-3, "mesh": {"size": 1e-4, "contact_size": 2e-6}},
                                               "load": {"value": [null, -1.6e-5]}})"));
    REQUIRE(small.result.status == Status::Converged);
    CHECK(small.contact.half_width == Approx(1e-3 * base.contact.half_width).epsilon(1e-6));
    CHECK(small.contact.max_pressure == Approx(base.contact.max_pressure).epsilon(1e-6));
    CHECK(small.hertz.error_l2 == Approx(base.hertz.error_l2).epsilon(1e-5));
  }
}
