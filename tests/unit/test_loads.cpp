// Consistent nodal forces: resultants and moments of tractions, pressures and gravity equal
// their integrals, on 3-node and 6-node triangles, straight and curved edges.
#include <catch2/catch.hpp>
#include <cmath>

#include "contactqp/model.hpp"
#include "model/model_parts.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

Eigen::Vector2d resultant(const Eigen::VectorXd& f) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (Eigen::Index k = 0; k < f.size() / 2; ++k) sum += f.segment<2>(2 * k);
  return sum;
}

Scene half_disc(int order, const std::string& loads) {
  return parse_scene(patched_scene("scenes/hertz.json", R"({"body": {"symmetry": false, "thickness": 0.5,
      "mesh": {"size": 0.2, "contact_size": 0.05, "order": )" +
                                                            std::to_string(order) + R"(}}, "load": )" + loads + "}"));
}

Eigen::VectorXd forces_of(const Scene& scene, Mesh* mesh_out = nullptr) {
  const Model model = build_model(scene);
  if (mesh_out) *mesh_out = model.mesh;
  return model.nodal_force;
}

}  // namespace

TEST_CASE("a traction on the flat top: resultant t · length · thickness", "[unit][loads]") {
  const int order = GENERATE(1, 2);
  CAPTURE(order);
  const Scene scene = half_disc(order, R"([{"type": "displacement", "boundary": "arc", "value": [0, 0]},
                                         {"type": "traction", "boundary": "top", "value": [0.3, -2.0]}])");
  const Eigen::Vector2d F = resultant(forces_of(scene));
  CHECK(F.x() == Approx(0.3 * 2.0 * 0.5));  // top length 2R, thickness 0.5
  CHECK(F.y() == Approx(-2.0 * 2.0 * 0.5));
}

TEST_CASE("6-node edges share a uniform traction 1/6, 2/3, 1/6", "[unit][loads]") {
  const Scene scene = half_disc(2, R"([{"type": "displacement", "boundary": "arc", "value": [0, 0]},
                                      {"type": "traction", "boundary": "top", "value": [0.0, 1.0]}])");
  Mesh mesh;
  const Eigen::VectorXd f = forces_of(scene, &mesh);
  for (const BoundaryFace& edge : mesh.boundaries.at("top")) {
    const double length = (mesh.nodes[edge.nodes[1]] - mesh.nodes[edge.nodes[0]]).norm();
    // The mid-side node belongs to this edge alone.
    CHECK(f[2 * edge.nodes[2] + 1] == Approx(2.0 / 3.0 * length * 0.5));
  }
}

TEST_CASE("a pressure on the curved arc pushes like p · chord", "[unit][loads]") {
  // A uniform pressure on the lower half circle of radius 1 has resultant p · 2R upwards
  // (the chord), exactly on the isoparametric 6-node edges only up to their geometric error.
  const int order = GENERATE(1, 2);
  CAPTURE(order);
  const Scene scene = half_disc(order, R"([{"type": "displacement", "boundary": "top", "value": [0, 0]},
                                         {"type": "pressure", "boundary": "arc", "value": 3.0}])");
  Mesh mesh;
  const Eigen::VectorXd f = forces_of(scene, &mesh);
  const Eigen::Vector2d F = resultant(f);
  CHECK(F.x() == Approx(0.0).margin(1e-12));
  CHECK(F.y() == Approx(3.0 * 2.0 * 0.5).epsilon(order == 1 ? 1e-12 : 1e-12));
  // ... and no moment about the centre (0, 1): a pressure on a circle points at its centre.
  double moment = 0;
  for (int k = 0; k < mesh.n_nodes(); ++k) {
    const Eigen::Vector2d r = mesh.nodes[k].head<2>() - Eigen::Vector2d(0, 1);
    moment += r.x() * f[2 * k + 1] - r.y() * f[2 * k];
  }
  CHECK(moment == Approx(0.0).margin(1e-12));
}

TEST_CASE("gravity: resultant ρ g · area · thickness, vertices of straight 6-node triangles get none",
          "[unit][loads]") {
  const int order = GENERATE(1, 2);
  CAPTURE(order);
  const Scene scene = parse_scene(R"({
    "material": {"E": 1, "nu": 0.3},
    "body": {"shape": "rectangle", "width": 2, "height": 0.5, "thickness": 3,
             "mesh": {"size": 0.1, "contact_size": 0.1, "order": )" +
                                  std::to_string(order) + R"(}},
    "load": [{"type": "displacement", "boundary": "top", "value": [0, 0]},
             {"type": "gravity", "density": 2.0, "g": [0, -9.81]}],
    "obstacle": {"type": "plane", "point": [0, -1], "normal": [0, 1]}})");
  Mesh mesh;
  const Eigen::VectorXd f = forces_of(scene, &mesh);
  CHECK(resultant(f).y() == Approx(-2.0 * 9.81 * 1.0 * 3.0));
  if (order == 2)
    for (int e = 0; e < mesh.n_elements(); ++e)
      for (int vertex = 0; vertex < 3; ++vertex) CHECK(f[2 * mesh.element(e)[vertex] + 1] == Approx(0.0).margin(1e-12));
}

TEST_CASE("a point force acts at the nearest node, halved on a symmetry plane", "[unit][loads]") {
  const std::string base = R"({"material": {"E": 1, "nu": 0.3},
    "body": {"shape": "rectangle", "width": 2, "height": 1, "symmetry": true, "mesh": {"size": 0.1, "contact_size": 0.1}},
    "obstacle": {"type": "plane", "point": [0, -1], "normal": [0, 1]}, "load": [
      {"type": "displacement", "boundary": "bottom", "value": [null, 0]},)";
  const Model off_axis =
      build_model(parse_scene(base + R"({"type": "point", "at": [0.52, 1.01], "value": [0.5, -4]}]})"));
  const Eigen::Vector2d F = resultant(off_axis.nodal_force);
  CHECK(F.isApprox(Eigen::Vector2d(0.5, -4)));
  REQUIRE(off_axis.warnings.size() == 1);  // (0.52, 1.01) is no node: the nearest takes it
  CHECK_THAT(off_axis.warnings[0], Catch::Matchers::Contains("load[1]"));
  const Model on_axis = build_model(parse_scene(base + R"({"type": "point", "at": [0, 1], "value": [0, -4]}]})"));
  CHECK(resultant(on_axis.nodal_force).y() == Approx(-2.0));
  CHECK(on_axis.warnings.empty());
}
