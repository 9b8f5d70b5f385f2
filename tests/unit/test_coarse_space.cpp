// The P1 level of quadratic meshes (contactqp/coarse_space.hpp, filled by assemble_qp): the
// multigrid hint of the PETSc solvers of K (docs/petsc-design.md, "The preconditioner").
#include <catch2/catch.hpp>

#include "contactqp/model.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

TEST_CASE("assemble_qp's P1 level: P times the coarse modes is the fine modes, a vertex its own column",
          "[unit][linear_solver]") {
  // hertz-order2: 6-node triangles with a symmetry plane (prescribed components at some
  // vertices, which still reach their mid-edge neighbours); hertz.json: linear, no level.
  Model linear = build_model(load_scene(source_path("scenes/hertz.json")));
  CHECK(assemble_qp(linear).coarse_space.empty());

  Model model = build_model(load_scene(source_path("scenes/hertz-order2.json")));
  const QuadraticProgram qp = assemble_qp(model);
  const CoarseSpace& coarse = qp.coarse_space;
  REQUIRE(!coarse.empty());
  REQUIRE(coarse.interpolation.rows() == qp.n_dofs());
  const Eigen::Index n_coarse = coarse.interpolation.cols();
  CHECK(n_coarse < qp.n_dofs() / 2);  // about a quarter of the DOFs in 2D
  REQUIRE(coarse.near_null_space.rows() == n_coarse);
  REQUIRE(coarse.near_null_space.cols() == qp.near_null_space.cols());
  REQUIRE(static_cast<Eigen::Index>(coarse.column_vertex.size()) == n_coarse);
  CHECK(coarse.block_size == 2);
  // P1 interpolation reproduces the translations on every free DOF, and the rotations up to the
  // curved edges' offsets (a mid-edge node on the circle is off its chord's midpoint).
  const Eigen::MatrixXd interpolated = coarse.interpolation * coarse.near_null_space;
  CHECK((interpolated.leftCols(2) - qp.near_null_space.leftCols(2)).cwiseAbs().maxCoeff() <= 1e-12);
  CHECK((interpolated - qp.near_null_space).cwiseAbs().maxCoeff() <= 0.02 * qp.near_null_space.cwiseAbs().maxCoeff());
  // A vertex's free DOF is its column: weight 1 there, nothing else in its row.
  const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = coarse.interpolation;
  int vertex_dofs = 0;
  for (Eigen::Index c = 0; c < n_coarse; ++c) {
    const int dof = coarse.column_dof[c];
    if (dof < 0) continue;
    ++vertex_dofs;
    CHECK(rows.row(dof).nonZeros() == 1);
    CHECK(rows.coeff(dof, c) == 1.0);
  }
  CHECK(vertex_dofs > 0);
  // Each vertex's columns are consecutive.
  for (Eigen::Index c = 1; c < n_coarse; ++c) CHECK(coarse.column_vertex[c] >= coarse.column_vertex[c - 1]);
}
