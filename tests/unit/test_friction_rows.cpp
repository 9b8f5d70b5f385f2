// The tangential rows of friction (friction.hpp): unit tangents orthogonal to each contact row's
// normal, in the obstacle's or the pair's frame; Tresca's bound s·w_i, Coulomb's μ; and an empty
// block without friction, so that a frictionless QP is today's.
#include <catch2/catch.hpp>

#include "contact/contact.hpp"
#include "contactqp/model.hpp"
#include "contactqp/scene.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

struct Assembled {
  Model model;
  QuadraticProgram qp;
};

Assembled assemble(const std::string& relative, const std::string& patch) {
  Assembled out;
  out.model = build_model(parse_scene(patched_scene(relative, patch), source_path(relative)));
  out.qp = assemble_qp(out.model);
  return out;
}

// Row r of a sparse matrix as a dense vector.
Eigen::VectorXd row(const SparseMatrix& A, int r) {
  const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = A;
  return Eigen::VectorXd(rows.row(r).transpose());
}

// Whether every DOF of a node is free (a node on a symmetry plane has one held).
bool all_free(const Model& model, int node) {
  for (int c = 0; c < model.dim; ++c)
    if (model.free_index[model.dim * node + c] < 0) return false;
  return true;
}

// Each tangential row is a unit vector orthogonal to its normal row and to the other tangents of
// its node (the rows of a node whose DOFs are all free).
void check_orthonormal(const Assembled& a) {
  const FrictionBlock& block = a.qp.friction;
  const int nd = block.n_directions, m = a.qp.n_constraints();
  REQUIRE(block.T.rows() == m * nd);
  REQUIRE(block.T.cols() == a.qp.n_dofs());
  int full = 0;
  for (int i = 0; i < m; ++i) {
    if (!all_free(a.model, a.model.candidates[i].node)) continue;
    const Eigen::VectorXd n = row(a.qp.B, i);
    ++full;
    for (int k = 0; k < nd; ++k) {
      const Eigen::VectorXd t = row(block.T, i * nd + k);
      CHECK(t.norm() == Approx(1).epsilon(1e-12));
      CHECK(std::abs(t.dot(n)) < 1e-12);
      for (int l = 0; l < k; ++l) CHECK(std::abs(t.dot(row(block.T, i * nd + l))) < 1e-12);
    }
  }
  CHECK(full > m / 2);
}

}  // namespace

TEST_CASE("a scene without friction has an empty friction block", "[unit][friction]") {
  const Assembled a = assemble("scenes/hertz.json", "{}");
  CHECK(a.qp.friction.empty());
  CHECK(a.qp.friction.T.rows() == 0);
  CHECK(a.qp.friction.offset.size() == 0);
}

TEST_CASE("Coulomb's rows on a 2D obstacle: one unit tangent per row, orthogonal to the normal", "[unit][friction]") {
  const Assembled a = assemble("scenes/hertz.json", R"({"contact": {"friction": {"coefficient": 0.3}}})");
  const FrictionBlock& block = a.qp.friction;
  CHECK(block.law == FrictionLaw::Coulomb);
  CHECK(block.n_directions == 1);
  REQUIRE(block.coefficient.size() == a.qp.n_constraints());
  CHECK(block.coefficient.minCoeff() == 0.3);
  CHECK(block.coefficient.maxCoeff() == 0.3);
  CHECK(block.threshold.size() == 0);  // the other law's vector stays empty
  CHECK(block.offset.size() == a.qp.n_constraints());
  CHECK(block.offset.isZero());  // a first step from rest, no prescribed tangential motion at the nodes
  check_orthonormal(a);
  // The plane's tangent is +x: a unit x displacement of every free DOF moves each row by 1.
  Eigen::VectorXd u = Eigen::VectorXd::Zero(a.qp.n_dofs());
  for (int node = 0; node < a.model.mesh.n_nodes(); ++node)
    if (a.model.free_index[2 * node] >= 0) u[a.model.free_index[2 * node]] = 1;
  const Eigen::VectorXd slip = block.T * u;
  for (int i = 0; i < a.qp.n_constraints(); ++i)
    CHECK(slip[i] == Approx(all_free(a.model, a.model.candidates[i].node) ? 1.0 : 0.0).margin(1e-14));
}

TEST_CASE("Tresca's rows in 3D: two tangents per row and the bound s times the tributary area", "[unit][friction]") {
  const Assembled a = assemble("scenes/hertz-sphere.json", R"({"obstacle": {"friction": {"threshold": 0.02}}})");
  const FrictionBlock& block = a.qp.friction;
  CHECK(block.law == FrictionLaw::Tresca);
  CHECK(block.n_directions == 2);
  REQUIRE(block.threshold.size() == a.qp.n_constraints());
  CHECK(block.coefficient.size() == 0);
  for (int i = 0; i < a.qp.n_constraints(); ++i)
    CHECK(block.threshold[i] == Approx(0.02 * a.model.candidates[i].tributary).epsilon(1e-15));
  check_orthonormal(a);
}

TEST_CASE("a pair's rows measure the relative tangential motion of the two sides", "[unit][friction]") {
  const Assembled a = assemble("scenes/two-cylinders.json", R"({"contact": {"friction": {"threshold": 0.001}}})");
  const FrictionBlock& block = a.qp.friction;
  REQUIRE(block.law == FrictionLaw::Tresca);
  const double thickness = a.model.scene.body.thickness;
  for (int i = 0; i < a.qp.n_constraints(); ++i)
    CHECK(block.threshold[i] == Approx(0.001 * a.model.candidates[i].tributary * thickness).epsilon(1e-15));
  // Every row over all DOFs: a common rigid translation leaves each row's position unchanged,
  // moving the node side alone by t moves it by one.
  const std::vector<detail::TangentialRow> rows = detail::tangential_rows(a.model);
  REQUIRE(rows.size() == static_cast<size_t>(a.qp.n_constraints()));
  const int dim = a.model.dim;
  for (size_t r = 0; r < rows.size(); ++r) {
    const Candidate& c = a.model.candidates[r];
    const Eigen::Vector3d t = detail::row_tangents(a.model, c).front();
    double common = 0, node_side = 0, approach = 0;
    for (const auto& [dof, value] : rows[r].entries) {
      common += value * (dof % dim == 0 ? 0.3 : -0.7);  // the translation (0.3, −0.7)
      if (dof / dim == c.node) node_side += value * t[dof % dim];
      // The node moved towards its partner along the common normal: no slip.
      if (dof / dim == c.node) approach += value * c.common_normal[dof % dim];
    }
    CHECK(std::abs(common) < 1e-14);
    CHECK(node_side == Approx(1).epsilon(1e-14));
    CHECK(c.common_normal.norm() == Approx(1).epsilon(1e-14));
    CHECK(c.common_normal.dot(c.normal) > 0.9);
    if (all_free(a.model, c.node)) CHECK(std::abs(approach) < 1e-14);  // on the plane t is the plane's normal
  }
}

TEST_CASE("a pair with friction presses along the common normal and a frictionless one along the face normal",
          "[unit][friction]") {
  // The normal row and the tangents of a frictional pair are orthogonal, so the normal force has
  // no share along the friction (two identical spheres' stick zone held p·r/R of it).
  const Assembled frictional =
      assemble("scenes/two-cylinders.json", R"({"contact": {"friction": {"coefficient": 0.3}}})");
  for (const Candidate& c : frictional.model.candidates) {
    CHECK((c.normal - c.common_normal).norm() < 1e-15);
    if (all_free(frictional.model, c.node))
      for (const Eigen::Vector3d& t : detail::row_tangents(frictional.model, c))
        CHECK(std::abs(t.dot(c.normal)) < 1e-15);
  }
  // Frictionless and μ = 0: today's rows (the face's normal, its gap), which lean off the common
  // normal away from the first touch.
  const Assembled plain = assemble("scenes/two-cylinders.json", "{}");
  const Assembled zero = assemble("scenes/two-cylinders.json", R"({"contact": {"friction": {"coefficient": 0}}})");
  REQUIRE(plain.model.candidates.size() == zero.model.candidates.size());
  REQUIRE(plain.model.candidates.size() == frictional.model.candidates.size());
  double lean = 0;
  for (size_t i = 0; i < plain.model.candidates.size(); ++i) {
    const Candidate &p = plain.model.candidates[i], &z = zero.model.candidates[i], &f = frictional.model.candidates[i];
    CHECK(z.normal == p.normal);
    CHECK(z.gap == p.gap);
    lean = std::max(lean, (p.normal - p.common_normal).norm());
    CHECK(f.gap == Approx(p.gap).epsilon(0.05).margin(1e-15));  // the same partner, along a direction r/R apart
  }
  CHECK(lean > 1e-3);
}

TEST_CASE("a rotated scene's rows are the scene's own rows turned", "[unit][friction]") {
  const char* friction = R"({"contact": {"friction": {"coefficient": 0.5}}})";
  const Assembled plain = assemble("scenes/hertz.json", friction);
  const Assembled turned = assemble("scenes/hertz-rotated.json", friction);
  REQUIRE(plain.qp.n_constraints() == turned.qp.n_constraints());
  // The same rows in the same order; the tangents turn with the plane, so each row's position
  // for the scene's own x displacement, turned, is the same.
  const Eigen::Matrix3d R = turned.model.rotation;
  Eigen::VectorXd a = Eigen::VectorXd::Zero(2 * plain.model.mesh.n_nodes()), b = a;
  for (int node = 0; node < plain.model.mesh.n_nodes(); ++node) {
    a[2 * node] = 1;
    b.segment<2>(2 * node) = R.topLeftCorner<2, 2>().col(0);
  }
  const auto rows_a = detail::tangential_rows(plain.model), rows_b = detail::tangential_rows(turned.model);
  for (size_t r = 0; r < rows_a.size(); ++r) {
    double pa = 0, pb = 0;
    for (const auto& [dof, value] : rows_a[r].entries) pa += value * a[dof];
    // The rotated scene's prescribed nodes have DOF frames: their components are along the
    // scene's axes, so the turned x displacement is (1, 0) there.
    for (const auto& [dof, value] : rows_b[r].entries) {
      const int node = dof / 2;
      const bool framed = !turned.model.frame_of_node.empty() && turned.model.frame_of_node[node] >= 0;
      pb += value * (framed ? (dof % 2 == 0 ? 1.0 : 0.0) : b[dof]);
    }
    CHECK(pb == Approx(pa).margin(1e-12));
  }
}
