// Mortar rows between two bodies ("rows": "mortar", docs/bodies.md): the contact patch test in
// 2D and 3D on meshes that do not match, with linear and quadratic elements (a uniform pressure
// passes the rows unchanged, which node-to-face rows do not), Hertz for two spheres and two
// cylinders, and every backend agreeing on the rows.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <string>

#include "contactqp/run.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

// Two blocks of one material, the lower mirrored below the plane of contact and held along the
// axis of the push at its far side, the upper pushed by δ at its top; sides free, symmetry
// planes through the axis: a uniform uniaxial stress, σ = E' δ / (2H) across the contact
// (E' = E in 3D, E/(1 − ν²) in plane strain, where the out-of-plane strain is held). The two
// meshes are 0.1 and 0.13: their nodes do not meet.
std::string stacked_blocks(int dim, int order, const char* rows) {
  char text[2048];
  if (dim == 3)
    std::snprintf(text, sizeof text, R"({
      "model": "solid",
      "bodies": [
        {"name": "upper", "shape": "box", "width": 1.0, "depth": 1.0, "height": 1.0, "symmetry": true,
         "mesh": {"size": 0.1, "contact_size": 0.1, "order": %d}, "material": {"E": 1.0, "nu": 0.3},
         "load": {"type": "displacement", "boundary": "top", "value": [null, null, -0.01]}},
        {"name": "lower", "shape": "box", "width": 1.0, "depth": 1.0, "height": 1.0, "symmetry": true, "mirror": true,
         "mesh": {"size": 0.13, "contact_size": 0.13, "order": %d}, "material": {"E": 1.0, "nu": 0.3},
         "load": {"type": "displacement", "boundary": "top", "value": [null, null, 0.0]}}
      ],
      "contact": {"pair": ["upper.bottom", "lower.bottom"], "rows": "%s"},
      "solver": {"backend": "active_set", "tol": 1e-10}
    })",
                  order, order, rows);
  else
    std::snprintf(text, sizeof text, R"({
      "model": "plane_strain",
      "bodies": [
        {"name": "upper", "shape": "rectangle", "width": 1.0, "height": 1.0, "symmetry": true,
         "mesh": {"size": 0.1, "contact_size": 0.1, "order": %d}, "material": {"E": 1.0, "nu": 0.3},
         "load": {"type": "displacement", "boundary": "top", "value": [null, -0.01]}},
        {"name": "lower", "shape": "rectangle", "width": 1.0, "height": 1.0, "symmetry": true, "mirror": true,
         "mesh": {"size": 0.13, "contact_size": 0.13, "order": %d}, "material": {"E": 1.0, "nu": 0.3},
         "load": {"type": "displacement", "boundary": "top", "value": [null, 0.0]}}
      ],
      "contact": {"pair": ["upper.bottom", "lower.bottom"], "rows": "%s"},
      "solver": {"backend": "active_set", "tol": 1e-10}
    })",
                  order, order, rows);
  return text;
}

// The largest relative departure of the node side's and the face side's nodal pressures from p
// (the face side's 6-node faces' vertices, which have no tributary area, report 0 and are
// passed over).
double largest_departure(const PairContact& pair, double p) {
  double largest = 0;
  for (const ContactProfilePoint& point : pair.profile) largest = std::max(largest, std::abs(point.pressure / p - 1));
  for (const ContactProfilePoint& point : pair.face_profile)
    if (point.pressure != 0) largest = std::max(largest, std::abs(point.pressure / p - 1));
  return largest;
}

// A shipped two-body scene run with the given rows: converged, one pair, compared with Hertz.
RunReport run_with_rows(const char* path, PairRows rows) {
  Scene scene = load_scene(source_path(path));
  REQUIRE(scene.pairs.size() == 1);
  scene.pairs[0].rows = rows;
  RunReport report = contactqp::run_scene(scene);
  REQUIRE(report.result.status == Status::Converged);
  REQUIRE(report.pairs.size() == 1);
  REQUIRE(report.pairs[0].hertz);
  return report;
}

// The zone (a in 3D, b in 2D) and p0 within 1 % of Hertz, the L2 pressure error within `l2`.
void check_near_hertz(const HertzComparison& hertz, double l2) {
  const double zone = hertz.dim == 3 ? hertz.error_contact_radius : hertz.error_half_width;
  CAPTURE(zone, hertz.error_max_pressure, hertz.error_l2);
  CHECK(std::abs(zone) <= 0.01);
  CHECK(std::abs(hertz.error_max_pressure) <= 0.01);
  CHECK(hertz.error_l2 <= l2);
}

}  // namespace

TEST_CASE("mortar rows pass the contact patch test on meshes that do not match, where node-to-face rows do not",
          "[validation][bodies][mortar]") {
  const int dim = GENERATE(2, 3);
  const int order = GENERATE(1, 2);
  CAPTURE(dim, order);
  const double p = dim == 3 ? 0.005 : 0.005 / (1 - 0.3 * 0.3);
  const RunReport mortar = contactqp::run_scene(parse_scene(stacked_blocks(dim, order, "mortar")));
  REQUIRE(mortar.result.status == Status::Converged);
  REQUIRE(mortar.pairs.size() == 1);
  const PairContact& pair = mortar.pairs[0];
  REQUIRE(pair.contact_nodes == static_cast<int>(pair.profile.size()));  // every row carries force
  const double departure = largest_departure(pair, p);
  CAPTURE(departure, pair.total_force);
  // The 2D rows are integrated exactly on flat sides; the 3D ones by points (mortar_rows.cpp):
  // 1e-4 measured, 6e-4 at the worst node.
  CHECK(departure <= (dim == 2 ? 1e-9 : 2e-3));
  CHECK(pair.total_force == Approx(p).epsilon(1e-8));  // 6e-10 measured in 3D
  CHECK(pair.action_reaction <= 1e-12);
  const RunReport nodes = contactqp::run_scene(parse_scene(stacked_blocks(dim, order, "node_to_face")));
  REQUIRE(nodes.result.status == Status::Converged);
  const double node_departure = largest_departure(nodes.pairs[0], p);
  CAPTURE(node_departure);
  CHECK(node_departure >= 0.03);  // 7 % to 20 % measured: why the mortar rows exist
}

TEST_CASE("mortar rows between two spheres: a and p0 within 1% of Hertz, the pressure twice as near",
          "[validation][bodies][mortar][3d][heavy]") {
  const RunReport mortar = run_with_rows("scenes/two-spheres.json", PairRows::Mortar);
  const HertzComparison& hertz = *mortar.pairs[0].hertz;
  // Measured: a +0.16 %, p0 −0.50 %, L2 2.4 % (node-to-face rows: +0.00 %, −1.99 %, 5.7 %), and
  // the face side's largest pressure within 0.01 % of the node side's (node-to-face: 43 %).
  check_near_hertz(hertz, 0.03);
  CHECK(mortar.pairs[0].face_max_pressure == Approx(mortar.pairs[0].max_pressure).epsilon(0.01));
  CHECK(mortar.pairs[0].action_reaction <= 1e-12);
  const RunReport nodes = run_with_rows("scenes/two-spheres.json", PairRows::NodeToFace);
  CHECK(nodes.pairs[0].hertz->error_l2 >= 2 * hertz.error_l2);
}

TEST_CASE("mortar rows between two cylinders: b and p0 within 1% of Hertz", "[validation][bodies][mortar]") {
  const RunReport report = run_with_rows("scenes/two-cylinders.json", PairRows::Mortar);
  // Measured: b −0.29 %, p0 +0.17 %, L2 0.94 % (node-to-face rows: −0.23 %, +0.09 %, 0.87 %).
  check_near_hertz(*report.pairs[0].hertz, 0.015);
}

TEST_CASE("mortar rows: every backend converged and agreeing", "[cross_backend][bodies][mortar]") {
  // Quadratic edges in 2D (rows with terms on their own side), linear faces in 3D (the patch
  // test above has the quadratic ones; the six backends on them take 8 s).
  const int dim = GENERATE(2, 3);
  CAPTURE(dim);
  const CompareReport report = compare_scene(parse_scene(stacked_blocks(dim, dim == 2 ? 2 : 1, "mortar")));
  CAPTURE(report.max_diff_u, report.max_diff_lambda, report.max_gap);
  CHECK(report.runs.size() == available_backends().size());
  CHECK(report.all_converged);
  CHECK(report.agree);
}
