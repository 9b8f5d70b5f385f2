// Nearly incompressible plane strain against Hertz: 3-node triangles lock as ν → 0.5,
// 6-node ones stiffen a little, the mixed formulation does not (docs/incompressible.md, where
// benchmarks/incompressible measures the whole table).
#include <catch2/catch.hpp>

#include "contactqp/post.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

struct Accuracy {
  HertzComparison hertz;
  std::vector<std::string> warnings;
};

Accuracy hertz_at(const std::string& scene, double nu, const std::string& formulation) {
  const std::string patch = R"({"material": {"nu": )" + std::to_string(nu) + R"(}, "body": {"formulation": ")" +
                            formulation + R"("}, "solver": {"backend": ")" +
                            (backend_available(Backend::Nlopt) ? "nlopt" : "active_set") + R"("}})";
  const SceneRun r = solve_scene(scene, patch);
  REQUIRE(r.result.status == Status::Converged);
  const auto hertz = compare_with_hertz(r.model, r.contact);
  REQUIRE(hertz.has_value());
  return {*hertz, r.model.warnings};
}

bool mentions(const std::vector<std::string>& warnings, const std::string& text) {
  for (const std::string& warning : warnings)
    if (warning.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("nu = 0.499 plane strain: 6-node triangles, and the mixed formulation, give Hertz's b and p0 within 5%",
          "[validation][hertz][mixed]") {
  const double nu = GENERATE(0.45, 0.49, 0.499);
  const std::string formulation = GENERATE(as<std::string>{}, "displacement", "mixed");
  CAPTURE(nu, formulation);
  const Accuracy a = hertz_at("scenes/hertz-order2.json", nu, formulation);
  CHECK(std::abs(a.hertz.error_half_width) < 0.05);
  CHECK(std::abs(a.hertz.error_max_pressure) < 0.05);
  if (formulation == "mixed") {
    // As accurate as at ν = 0.3 on this mesh (b −0.04%, p0 +0.28%): nothing locks.
    CHECK(std::abs(a.hertz.error_half_width) < 0.005);
    CHECK(std::abs(a.hertz.error_max_pressure) < 0.005);
    CHECK(a.warnings.empty());
  }
  // The displacement formulation warns where its locking shows.
  if (formulation == "displacement") CHECK(mentions(a.warnings, "formulation\": \"mixed") == (nu > 0.49));
}

TEST_CASE("3-node triangles lock at nu = 0.499, and say so", "[validation][hertz][mixed]") {
  const Accuracy a = hertz_at("scenes/hertz.json", 0.499, "displacement");
  CHECK(a.hertz.error_max_pressure > 0.2);  // measured +40%
  CHECK(mentions(a.warnings, "material.nu = 0.499 with 3-node triangles in plane strain: they lock"));
  CHECK(mentions(a.warnings, "\"formulation\": \"mixed\""));
}
