// Assembly: K symmetric positive definite after eliminating Dirichlet DOFs, prescribed
// displacements on the right-hand side, and the patch test on a real (graded, curved) mesh.
#include <catch2/catch.hpp>

#include "contactqp/cholesky.hpp"
#include "contactqp/model.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

Scene small_scene(int order, bool symmetry) {
  Scene scene =
      parse_scene(patched_scene("scenes/hertz.json", R"({"body": {"mesh": {"size": 0.2, "contact_size": 0.02}}})"));
  scene.body.mesh.order = order;
  scene.body.symmetry = symmetry;
  if (!symmetry) scene.loads[0].as<DisplacementLoad>()->value[0] = 0.0;  // the full disc needs u_x held somewhere
  return scene;
}

}  // namespace

TEST_CASE("K is symmetric positive definite after elimination", "[unit][assembly]") {
  const int order = GENERATE(1, 2);
  const bool symmetry = GENERATE(true, false);
  CAPTURE(order, symmetry);
  Model model = build_model(small_scene(order, symmetry));
  const QuadraticProgram qp = assemble_qp(model);
  REQUIRE(qp.n_dofs() == model.n_free);
  const SparseMatrix asymmetry = qp.K - SparseMatrix(qp.K.transpose());
  CHECK(asymmetry.norm() <= 1e-12 * qp.K.norm());
  const CholeskyFactor factor(qp.K);
  CHECK(factor.ok());
  // The prescribed displacement enters only through f: with δ = 0 there is no load at all.
  CHECK(qp.f.norm() > 0);
  Scene unloaded = small_scene(order, symmetry);
  unloaded.loads[0].as<DisplacementLoad>()->value[1] = 0.0;
  Model unloaded_model = build_model(unloaded);
  CHECK(assemble_qp(unloaded_model).f.norm() == 0.0);
}

TEST_CASE("patch test: a linear displacement field is reproduced exactly", "[unit][assembly]") {
  // Prescribe u = a + A x on every boundary node; the interior must follow exactly, on a
  // graded unstructured mesh, with straight (order 1) and curved isoparametric (order 2) sides.
  const int order = GENERATE(1, 2);
  CAPTURE(order);
  Model model = build_model(small_scene(order, false));
  const Eigen::Vector2d a(1e-3, -2e-3);
  Eigen::Matrix2d A;
  A << 2e-3, -1e-3, 5e-4, -3e-3;
  std::vector<bool> on_boundary(model.mesh.n_nodes(), false);
  for (const auto& [name, edges] : model.mesh.boundaries)
    for (int node : boundary_nodes(model.mesh, name)) on_boundary[node] = true;
  model.n_free = 0;
  for (int node = 0; node < model.mesh.n_nodes(); ++node) {
    const Eigen::Vector2d u = a + A * model.mesh.nodes[node].head<2>();
    for (int c = 0; c < 2; ++c) {
      model.free_index[2 * node + c] = on_boundary[node] ? -1 : model.n_free++;
      model.prescribed[2 * node + c] = on_boundary[node] ? u[c] : 0.0;
    }
  }
  model.candidates.clear();
  const QuadraticProgram qp = assemble_qp(model);
  const CholeskyFactor factor(qp.K);
  REQUIRE(factor.ok());
  const Eigen::VectorXd full = full_displacement(model, factor.solve(qp.f));
  double worst = 0;
  for (int node = 0; node < model.mesh.n_nodes(); ++node)
    worst = std::max(worst, (full.segment<2>(2 * node) - (a + A * model.mesh.nodes[node].head<2>())).norm());
  CHECK(worst <= 1e-12);
}

TEST_CASE("the half-disc mesh is graded and its boundaries are where the scene says", "[unit][mesh]") {
  Model model = build_model(small_scene(1, true));
  const Mesh& mesh = model.mesh;
  const double R = model.scene.body.radius;
  for (int node : boundary_nodes(mesh, "arc"))
    CHECK(((mesh.nodes[node].head<2>() - Eigen::Vector2d(0, R)).norm()) == Approx(R).epsilon(1e-12));
  for (int node : boundary_nodes(mesh, "top")) CHECK(mesh.nodes[node].y() == Approx(R).epsilon(1e-14));
  for (int node : boundary_nodes(mesh, "symmetry")) CHECK(mesh.nodes[node].x() == 0.0);
  // Edges along the candidate arc are near contact_size; far from it near size.
  double shortest = 1e300, longest = 0;
  for (const BoundaryFace& edge : mesh.boundaries.at("arc")) {
    const double length = (mesh.nodes[edge.nodes[0]] - mesh.nodes[edge.nodes[1]]).norm();
    shortest = std::min(shortest, length);
    longest = std::max(longest, length);
  }
  const MeshSpec& spec = model.scene.body.mesh;
  CHECK(shortest == Approx(spec.contact_size).epsilon(0.3));
  CHECK(longest <= 1.3 * spec.size);
  CHECK(longest >= 4 * spec.contact_size);  // graded, not uniformly fine
  // Every candidate faces the plane and lies within the candidate distance.
  REQUIRE(!model.candidates.empty());
  for (const Candidate& candidate : model.candidates) {
    CHECK(candidate.gap <= model.max_gap);
    CHECK(candidate.tributary > 0);
  }
}
