// The P1 level of a mesh of quadratic elements, as data for a multigrid solver of K
// (QuadraticProgram::coarse_space): the nodal interpolation from the vertices' linear field to
// every node (P2 → P1, "p-multigrid"). An algebraic multigrid then works on PᵀKP, a P1
// stiffness matrix with an eighth of the rows (3D) and a third of the nonzeros per row, which
// is far cheaper to coarsen than K itself, and low-order AMG stays optimal as a preconditioner
// for high-order simplices (Olson 2007). No backend needs it for a correct answer.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace contactqp {

struct CoarseSpace {
  // n_free × n_coarse, in the DOF frames of K: a vertex's DOF takes its vertex's value, a
  // mid-edge node's the mean of its edge's two vertices (the frames rotated where they differ);
  // the columns are dim per vertex node, every component (a prescribed one too: it still
  // reaches the free DOFs of its mid-edge neighbours), column dim·v + c the component c of
  // vertex v in that vertex's DOF frame. Empty for linear elements.
  Eigen::SparseMatrix<double> interpolation;
  // n_coarse × k: the rigid-body modes at the vertices, every component, in the same frames and
  // scaling as QuadraticProgram::near_null_space, so that P times them is the fine modes.
  Eigen::MatrixXd near_null_space;
  // n_coarse: the free DOF at the vertex that column c interpolates to with weight 1, or −1
  // when that component is prescribed. A change of variables at a node (the petsc backend's
  // bound form) applies to its vertex columns through it.
  std::vector<int> column_dof;
  // n_coarse: the vertex (numbered among the vertex nodes) each column belongs to; a vertex's
  // columns are consecutive, all its dim components when none was left out.
  std::vector<int> column_vertex;
  int block_size = 1;  // dim: columns per vertex

  bool empty() const { return interpolation.cols() == 0; }
};

}  // namespace contactqp
