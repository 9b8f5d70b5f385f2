// fill_matrix() and owned_rows() (petsc_matrix.hpp).
#include "petsc_matrix.hpp"

#include <vector>

namespace contactqp::detail {
namespace {

using Column = Eigen::SparseMatrix<double>::InnerIterator;

// Sets rows [from, to) of the matrix (rows in `order`) into `target`, a matrix or a
// preallocator: row p is DOF j = order.dof(p), M's column j by symmetry.
PetscErrorCode set_rows(Mat target, const Eigen::SparseMatrix<double>& M, const RowOrder& order, PetscInt from,
                        PetscInt to, InsertMode mode) {
  std::vector<PetscInt> columns;
  std::vector<PetscScalar> values;
  for (PetscInt row = from; row < to; ++row) {
    columns.clear();
    values.clear();
    for (Column it(M, order.dof(row)); it; ++it) {
      columns.push_back(order.row(static_cast<int>(it.row())));
      values.push_back(it.value());
    }
    if (columns.empty()) continue;
    PetscCall(
        MatSetValues(target, 1, &row, static_cast<PetscInt>(columns.size()), columns.data(), values.data(), mode));
  }
  return 0;
}

}  // namespace

RowOrder::RowOrder(const std::vector<int>& row_of_dof) : row_(row_of_dof), dof_(row_of_dof.size()) {
  for (std::size_t j = 0; j < row_.size(); ++j) dof_[row_[j]] = static_cast<int>(j);
}

void RowOrder::to_local(const Eigen::VectorXd& full, PetscInt first, PetscInt end, PetscScalar* local) const {
  for (PetscInt row = first; row < end; ++row) local[row - first] = full[dof(row)];
}

Eigen::VectorXd RowOrder::to_dofs(const PetscScalar* all, int n) const {
  Eigen::VectorXd out(n);
  for (int j = 0; j < n; ++j) out[j] = all[row(j)];
  return out;
}

PetscErrorCode owned_rows(PetscInt n, PetscInt* first, PetscInt* end) {
  PetscInt local = PETSC_DECIDE, global = n;
  PetscCall(PetscSplitOwnership(PETSC_COMM_WORLD, &local, &global));
  PetscCallMPI(MPI_Scan(&local, end, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  *first = *end - local;
  return 0;
}

PetscErrorCode fill_matrix(Mat A, const Eigen::SparseMatrix<double>& M, bool share, const RowOrder& order,
                           PetscInt first, PetscInt end, const char** step) {
  const PetscInt n = M.rows(), local = end - first;
  PetscErrorCode code = 0;
  if (!share) {
    *step = "MatMPIAIJSetPreallocation";
    std::vector<PetscInt> diagonal_block(local, 0), off_diagonal_block(local, 0);
    for (PetscInt row = first; row < end; ++row)
      for (Column it(M, order.dof(row)); it; ++it) {
        const PetscInt column = order.row(static_cast<int>(it.row()));
        ++(column >= first && column < end ? diagonal_block : off_diagonal_block)[row - first];
      }
    if ((code = MatMPIAIJSetPreallocation(A, 0, diagonal_block.data(), 0, off_diagonal_block.data()))) return code;
    if ((code = MatSeqAIJSetPreallocation(A, 0, diagonal_block.data()))) return code;  // -mat_type seqaij
    *step = "MatSetValues";
    if ((code = set_rows(A, M, order, first, end, INSERT_VALUES))) return code;
  } else {
    *step = "MATPREALLOCATOR";
    Mat pattern = nullptr;
    if ((code = MatCreate(PETSC_COMM_WORLD, &pattern))) return code;
    code = MatSetType(pattern, MATPREALLOCATOR);
    if (!code) code = MatSetSizes(pattern, local, local, n, n);
    if (!code) code = MatSetUp(pattern);
    if (!code) code = set_rows(pattern, M, order, 0, n, ADD_VALUES);
    if (!code) code = MatAssemblyBegin(pattern, MAT_FINAL_ASSEMBLY);
    if (!code) code = MatAssemblyEnd(pattern, MAT_FINAL_ASSEMBLY);
    if (!code) code = MatPreallocatorPreallocate(pattern, PETSC_TRUE, A);
    MatDestroy(&pattern);
    if (code) return code;
    *step = "MatSetValues";
    if ((code = set_rows(A, M, order, 0, n, ADD_VALUES))) return code;
  }
  *step = "MatAssembly";
  if ((code = MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY))) return code;
  return MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
}

}  // namespace contactqp::detail
