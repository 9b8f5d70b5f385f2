// An Eigen matrix into a distributed PETSc AIJ matrix, for the PETSc solver of K
// (petsc_solver.cpp) and the petsc backend's bound QP (petsc_bound_qp.cpp). Internal to cqp_qp.
#pragma once

#include <petscmat.h>

#include <Eigen/SparseCore>
#include <vector>

namespace contactqp::detail {

// The rows of the distributed matrix in another order than the DOFs (qp.hpp's
// distributed_row, a mesh partition's parts one after another): the identity when empty.
class RowOrder {
 public:
  RowOrder() = default;
  explicit RowOrder(const std::vector<int>& row_of_dof);
  PetscInt row(int dof) const { return row_.empty() ? dof : row_[dof]; }
  int dof(PetscInt row) const { return dof_.empty() ? static_cast<int>(row) : dof_[row]; }
  // This rank's rows [first, end) of a vector every rank holds whole in DOF order.
  void to_local(const Eigen::VectorXd& full, PetscInt first, PetscInt end, PetscScalar* local) const;
  // A whole vector in row order (gathered) back in DOF order.
  Eigen::VectorXd to_dofs(const PetscScalar* all, int n) const;

 private:
  std::vector<int> row_, dof_;
};

// The rows [first, end) of an n-row matrix that this rank owns: PETSc's split
// (PetscSplitOwnership), contiguous blocks in rank order.
PetscErrorCode owned_rows(PetscInt n, PetscInt* first, PetscInt* end);

// Preallocates and fills A (created, sized n × n with the local rows of owned_rows(), its type
// set) from M, which is symmetric with both triangles stored, so that column j of the
// column-major M is row j. Whole (share false): every rank holds all of M and sets the rows it
// owns. Share: every rank holds its share of the matrix (the sum of the shares is the matrix,
// qp.hpp's K_is_rank_share) and adds all of it (ADD_VALUES; PETSc sends the entries of other
// ranks' rows at assembly), preallocated from the union of the shares' patterns
// (MATPREALLOCATOR), since no rank knows a whole row at its boundary. On failure `step` names
// the PETSc call that failed. Collective.
// M's DOF order becomes the matrix's row order through `order`.
PetscErrorCode fill_matrix(Mat A, const Eigen::SparseMatrix<double>& M, bool share, const RowOrder& order,
                           PetscInt first, PetscInt end, const char** step);

}  // namespace contactqp::detail
