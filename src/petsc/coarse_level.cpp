// CoarseLevel (coarse_level.hpp): the P1 level's interpolation and modes in PETSc.
#include "coarse_level.hpp"

#include <algorithm>
#include <numeric>

#include "petsc_runtime.hpp"

namespace contactqp::detail {

CoarseLevel::~CoarseLevel() {
  if (petsc_finalized()) return;
  if (P_) MatDestroy(&P_);
  if (modes_) MatNullSpaceDestroy(&modes_);
}

PetscErrorCode CoarseLevel::create(const CoarseLevelInput& input, const RowOrder& order, PetscInt first, PetscInt end,
                                   Mat A) {
  PetscFunctionBeginUser;
  const Eigen::SparseMatrix<double>& P = *input.interpolation;
  const std::vector<int>& vertex_of = *input.column_vertex;
  const PetscInt n = P.rows();
  const int n_columns = static_cast<int>(P.cols());
  const MPI_Comm comm = PETSC_COMM_WORLD;
  PetscMPIInt rank = 0, ranks = 1;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &ranks));
  std::vector<PetscInt> starts(ranks + 1, 0);
  PetscCallMPI(MPI_Allgather(&first, 1, MPIU_INT, starts.data(), 1, MPIU_INT, comm));
  starts[ranks] = n;
  auto owner = [&](PetscInt row) {
    return static_cast<int>(std::upper_bound(starts.begin(), starts.end() - 1, row) - starts.begin()) - 1;
  };

  // Each vertex: where its own rows are (else its smallest row), its columns.
  const int n_vertices = n_columns ? *std::max_element(vertex_of.begin(), vertex_of.end()) + 1 : 0;
  std::vector<PetscInt> home(n_vertices, n), smallest(n_vertices, n);
  std::vector<int> count(n_vertices, 0);
  for (int c = 0; c < n_columns; ++c) {
    ++count[vertex_of[c]];
    const int row = (*input.vertex_row)[c];
    if (row >= 0) home[vertex_of[c]] = std::min(home[vertex_of[c]], order.row(row));
    for (Eigen::SparseMatrix<double>::InnerIterator it(P, c); it; ++it)
      smallest[vertex_of[c]] = std::min(smallest[vertex_of[c]], order.row(static_cast<int>(it.row())));
  }
  for (int v = 0; v < n_vertices; ++v)
    if (home[v] == n) home[v] = smallest[v] < n ? smallest[v] : 0;
  std::vector<int> vertices(n_vertices);
  std::iota(vertices.begin(), vertices.end(), 0);
  std::stable_sort(vertices.begin(), vertices.end(), [&](int a, int b) { return home[a] < home[b]; });
  std::vector<PetscInt> vertex_start(n_vertices, 0);
  PetscInt next = 0, local_columns = 0;
  for (int v : vertices) {
    vertex_start[v] = next;
    next += count[v];
    if (owner(home[v]) == rank) local_columns += count[v];
  }
  column_.assign(n_columns, 0);
  std::vector<int> seen(n_vertices, 0);
  for (int c = 0; c < n_columns; ++c) column_[c] = vertex_start[vertex_of[c]] + seen[vertex_of[c]]++;
  bool blocks = input.block_size > 1;
  for (int v = 0; v < n_vertices && blocks; ++v) blocks = count[v] == input.block_size;

  // P, rows [first, end): preallocated per row, within and outside this rank's columns.
  PetscInt column_first = 0;
  PetscCallMPI(MPI_Exscan(&local_columns, &column_first, 1, MPIU_INT, MPI_SUM, comm));
  if (rank == 0) column_first = 0;
  const PetscInt column_end = column_first + local_columns;
  std::vector<PetscInt> diagonal(end - first, 0), off_diagonal(end - first, 0);
  struct Entry {
    PetscInt row, column;
    double value;
  };
  std::vector<Entry> entries;
  for (int c = 0; c < n_columns; ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(P, c); it; ++it) {
      const PetscInt row = order.row(static_cast<int>(it.row()));
      if (row < first || row >= end || it.value() == 0) continue;
      const PetscInt column = column_[c];
      ++(column >= column_first && column < column_end ? diagonal : off_diagonal)[row - first];
      entries.push_back({row, column, it.value()});
    }
  PetscCall(MatCreate(comm, &P_));
  PetscCall(MatSetSizes(P_, end - first, local_columns, n, n_columns));
  MatType type = nullptr;
  PetscCall(MatGetType(A, &type));
  PetscCall(MatSetType(P_, type));
  if (blocks) PetscCall(MatSetBlockSizes(P_, 1, input.block_size));
  PetscCall(MatSeqAIJSetPreallocation(P_, 0, diagonal.data()));
  PetscCall(MatMPIAIJSetPreallocation(P_, 0, diagonal.data(), 0, off_diagonal.data()));
  for (const Entry& e : entries) PetscCall(MatSetValues(P_, 1, &e.row, 1, &e.column, &e.value, INSERT_VALUES));
  PetscCall(MatAssemblyBegin(P_, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(P_, MAT_FINAL_ASSEMBLY));

  // The modes on the level, orthonormalised (modified Gram–Schmidt) as MatNullSpace wants.
  const Eigen::MatrixXd* modes = input.modes;
  if (!modes || modes->cols() == 0 || modes->rows() != n_columns) PetscFunctionReturn(0);
  std::vector<Vec> vectors(modes->cols());
  for (Eigen::Index k = 0; k < modes->cols(); ++k) {
    PetscCall(MatCreateVecs(P_, &vectors[k], nullptr));
    PetscScalar* local = nullptr;
    PetscCall(VecGetArray(vectors[k], &local));
    for (int c = 0; c < n_columns; ++c)
      if (column_[c] >= column_first && column_[c] < column_end) local[column_[c] - column_first] = (*modes)(c, k);
    PetscCall(VecRestoreArray(vectors[k], &local));
    for (Eigen::Index j = 0; j < k; ++j) {
      PetscScalar dot = 0;
      PetscCall(VecDot(vectors[k], vectors[j], &dot));
      PetscCall(VecAXPY(vectors[k], -dot, vectors[j]));
    }
    PetscReal norm = 0;
    PetscCall(VecNormalize(vectors[k], &norm));
  }
  PetscCall(MatNullSpaceCreate(comm, PETSC_FALSE, static_cast<PetscInt>(vectors.size()), vectors.data(), &modes_));
  for (Vec& v : vectors) PetscCall(VecDestroy(&v));
  PetscFunctionReturn(0);
}

}  // namespace contactqp::detail
