// The petsc backend's change of variables (src/petsc/bound_form.hpp): with u = Q v, row i of
// B u is exactly the variable v at bounded[i]; a node's rows against another body's face get a
// change on that node's DOFs alone, so QᵀKQ stays about as sparse as K; rows that share all
// their DOFs (a node with two rows) keep their group's dense change; the P1 level's columns
// carry the same change (the two spheres' 10-node tetrahedra).
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "contactqp/model.hpp"
#include "contactqp/scene.hpp"
#include "petsc/bound_form.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

// Row i of M is the unit vector at column[i] (to round-off relative to the row of B it came from).
void check_rows_select(const SparseMatrix& M, const SparseMatrix& B, const std::vector<int>& column) {
  const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = M, B_rows = B;
  for (int i = 0; i < rows.rows(); ++i) {
    CAPTURE(i, column[i]);
    REQUIRE(column[i] >= 0);
    const double scale = std::max(1.0, B_rows.row(i).norm());
    double at_column = 0, elsewhere = 0;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, i); it; ++it)
      (it.col() == column[i] ? at_column : elsewhere) += std::abs(it.value());
    CHECK(std::abs(at_column - 1) <= 1e-12 * scale);
    CHECK(elsewhere <= 1e-12 * scale);
  }
}

// A hand-made QP of n DOFs: K tridiagonal (SPD), B's rows given as (column, value) lists.
QuadraticProgram small_qp(int n, const std::vector<std::vector<std::pair<int, double>>>& rows) {
  QuadraticProgram qp;
  std::vector<Eigen::Triplet<double>> k, b;
  for (int j = 0; j < n; ++j) {
    k.emplace_back(j, j, 4.0);
    if (j + 1 < n) {
      k.emplace_back(j, j + 1, -1.0);
      k.emplace_back(j + 1, j, -1.0);
    }
  }
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (const auto& [j, value] : rows[i]) b.emplace_back(static_cast<int>(i), j, value);
  qp.K.resize(n, n);
  qp.K.setFromTriplets(k.begin(), k.end());
  qp.B.resize(static_cast<int>(rows.size()), n);
  qp.B.setFromTriplets(b.begin(), b.end());
  qp.f = VectorXd::LinSpaced(n, 1.0, 2.0);
  qp.g = VectorXd::Constant(static_cast<int>(rows.size()), 0.1);
  return qp;
}

detail::BoundForm bound_form_of(const QuadraticProgram& qp) {
  detail::BoundForm form;
  std::string message;
  const bool made = detail::make_bound_form(qp, {}, form, message);
  CAPTURE(message);
  REQUIRE(made);
  return form;
}

}  // namespace

TEST_CASE("the bound form: rows that share DOFs with their neighbours change only their own DOFs", "[petsc]") {
  // Nodes 0-2 (DOFs 0-5) against a face of nodes 3-5 (DOFs 6-11): each row is the node's normal
  // displacement minus the face's under it, each face node under two of the nodes.
  const std::vector<std::vector<std::pair<int, double>>> rows = {
      {{0, 0.6}, {1, 0.8}, {6, -0.3}, {7, -0.4}, {8, -0.3}, {9, -0.4}},
      {{2, 0.6}, {3, 0.8}, {8, -0.3}, {9, -0.4}, {10, -0.3}, {11, -0.4}},
      {{4, 0.6}, {5, 0.8}, {10, -0.3}, {11, -0.4}, {6, -0.3}, {7, -0.4}}};
  const QuadraticProgram qp = small_qp(12, rows);
  const detail::BoundForm form = bound_form_of(qp);
  check_rows_select(qp.B * form.Q, qp.B, form.problem.bounded);
  // Each row's variable is one of its node's DOFs, and the face keeps its DOFs (u = v there).
  CHECK(form.problem.bounded == std::vector<int>{0, 2, 4});
  const Eigen::SparseMatrix<double, Eigen::RowMajor> Q_rows = form.Q;
  for (int j = 6; j < 12; ++j) CHECK((VectorXd(Q_rows.row(j).transpose()) - VectorXd::Unit(12, j)).norm() == 0);
  // The same QP: A = QᵀKQ, b = Qᵀf.
  CHECK((form.problem.A - SparseMatrix(form.Q.transpose() * qp.K * form.Q)).norm() <= 1e-14 * qp.K.norm());
  CHECK((form.problem.b - form.Q.transpose() * qp.f).norm() == 0);
  // A node's DOFs depend on its own new variables and the face's, never on another node's.
  for (int i = 0; i < 6; ++i)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(Q_rows, i); it; ++it)
      if (it.col() < 6) CHECK(it.col() / 2 == i / 2);
}

TEST_CASE("the bound form: a node's two rows on the same DOFs keep their group's dense change", "[petsc]") {
  // Node 0 (DOFs 0, 1) touches two obstacles: neither row has a DOF of its own.
  const std::vector<std::vector<std::pair<int, double>>> rows = {{{0, 1.0}, {1, 0.5}}, {{0, -0.5}, {1, 1.0}}};
  const QuadraticProgram qp = small_qp(4, rows);
  const detail::BoundForm form = bound_form_of(qp);
  check_rows_select(qp.B * form.Q, qp.B, form.problem.bounded);
  CHECK(form.problem.bounded == std::vector<int>{0, 1});
}

TEST_CASE("the bound form of two bodies in contact: exact rows, as sparse as K, the P1 level's too",
          "[petsc][bodies]") {
  const std::string scene = GENERATE(as<std::string>{}, "scenes/two-cylinders.json", "scenes/two-spheres.json");
  CAPTURE(scene);
  // Both coarser at the contact, to keep the test short (the shipped spheres' 383 rows were one
  // dense group of their DOFs before).
  Scene parsed = load_scene(source_path(scene));
  for (SceneBody& body : parsed.bodies) body.body.mesh.contact_size *= 2.5;
  Model model = build_model(parsed);
  const QuadraticProgram qp = assemble_qp(model);
  const detail::BoundForm form = bound_form_of(qp);
  check_rows_select(qp.B * form.Q, qp.B, form.problem.bounded);
  const double fill = static_cast<double>(form.problem.A.nonZeros()) / static_cast<double>(qp.K.nonZeros());
  CAPTURE(qp.n_dofs(), qp.n_constraints(), fill);
  CHECK(fill <= 1.2);
  if (!qp.coarse_space.empty()) {
    // Where a row's DOFs are all vertex DOFs its coarse variable is its row too: B P_c = B Q (Q⁻¹ P Q_c).
    const SparseMatrix coarse_rows = qp.B * form.Q * form.problem.coarse_interpolation;
    int on_coarse_level = 0;
    for (int i = 0; i < qp.n_constraints(); ++i) {
      if (form.problem.coarse_bounded[i] < 0) continue;
      ++on_coarse_level;
      const SparseMatrix row = coarse_rows.row(i);
      const double at_column = row.coeff(0, form.problem.coarse_bounded[i]);
      CHECK(std::abs(at_column - 1) <= 1e-12);
      CHECK(row.cwiseAbs().sum() - std::abs(at_column) <= 1e-12);
    }
    CHECK(on_coarse_level > 0);
  }
}

TEST_CASE("the bound form: a tangential row of round-off leaves the other nodes' changes their own", "[petsc]") {
  // The first case's three node-against-face rows, with Tresca friction (one direction each).
  // Node 2's tangent lies along a prescribed direction: on its free DOFs only round-off is left
  // (as a node on a symmetry plane gave, 1e-32, on mindlin-spheres.json refined to 7.8e5 DOFs).
  // Round-off is no coefficient: that row has no variable (λ_T = 0 there), and every node keeps
  // a change of variables on its own DOFs. Before, the row had no DOF of its own to pivot on, the
  // whole group went to one dense change (at scale a QR over the whole contact zone), and here
  // its rows were refused as linearly dependent.
  const std::vector<std::vector<std::pair<int, double>>> rows = {
      {{0, 0.6}, {1, 0.8}, {6, -0.3}, {7, -0.4}, {8, -0.3}, {9, -0.4}},
      {{2, 0.6}, {3, 0.8}, {8, -0.3}, {9, -0.4}, {10, -0.3}, {11, -0.4}},
      {{4, 0.6}, {5, 0.8}, {10, -0.3}, {11, -0.4}, {6, -0.3}, {7, -0.4}}};
  QuadraticProgram qp = small_qp(12, rows);
  const std::vector<std::vector<std::pair<int, double>>> tangents = {
      {{0, -0.8}, {1, 0.6}, {6, 0.4}, {7, -0.3}, {8, 0.4}, {9, -0.3}},
      {{2, -0.8}, {3, 0.6}, {8, 0.4}, {9, -0.3}, {10, 0.4}, {11, -0.3}},
      {{4, 3e-33}, {5, -4e-33}, {10, 2e-33}, {11, 1e-33}}};
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t i = 0; i < tangents.size(); ++i)
    for (const auto& [j, value] : tangents[i]) t.emplace_back(static_cast<int>(i), j, value);
  qp.friction.law = FrictionLaw::Tresca;
  qp.friction.n_directions = 1;
  qp.friction.T.resize(3, 12);
  qp.friction.T.setFromTriplets(t.begin(), t.end());
  qp.friction.offset = VectorXd::Zero(3);
  qp.friction.threshold = VectorXd::Constant(3, 0.05);
  const detail::BoundForm form = bound_form_of(qp);
  check_rows_select(qp.B * form.Q, qp.B, form.problem.bounded);
  // Nodes 0 and 1: normal and tangent on their two DOFs; node 2: the normal only.
  CHECK(form.problem.bounded == std::vector<int>{0, 2, 4});
  REQUIRE(form.problem.tangential.size() == 3);
  CHECK(form.problem.tangential[0] == 1);
  CHECK(form.problem.tangential[1] == 3);
  CHECK(form.problem.tangential[2] == -1);
  // The face keeps its DOFs, and a node's DOFs depend on no other node's.
  const Eigen::SparseMatrix<double, Eigen::RowMajor> Q_rows = form.Q;
  for (int j = 6; j < 12; ++j) CHECK((VectorXd(Q_rows.row(j).transpose()) - VectorXd::Unit(12, j)).norm() == 0);
  for (int i = 0; i < 6; ++i)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(Q_rows, i); it; ++it)
      if (it.col() < 6) CHECK(it.col() / 2 == i / 2);
}
