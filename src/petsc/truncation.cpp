// TruncatedHierarchy (truncation.hpp): local Galerkin updates of a kept multigrid hierarchy.
#include "truncation.hpp"

#include <Eigen/SparseCore>

#include <algorithm>
#include <unordered_map>

#include "contactqp/timer.hpp"

namespace contactqp::detail {
namespace {

// An entry of a change of a level operator, in global indices. Each rank holds a part of the
// change; the parts sum to it, and since every step below is linear each rank carries its own
// part down the levels.
struct Entry {
  PetscInt row, column;
  double value;
};

bool is_galerkin_amg(PC pc) {
  PetscBool yes = PETSC_FALSE;
  PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(pc), &yes, PCGAMG, PCML, "");
  return yes;
}

// Rows `rows` (global, increasing) of P as an Eigen matrix with P's global column indices: the
// rows may be other ranks'. Collective (MatCreateSubMatrices), also with no rows.
PetscErrorCode rows_of(Mat P, const std::vector<PetscInt>& rows, Eigen::SparseMatrix<double, Eigen::RowMajor>& out) {
  PetscFunctionBeginUser;
  PetscInt columns = 0;
  PetscCall(MatGetSize(P, nullptr, &columns));
  IS row_set = nullptr, all_columns = nullptr;
  PetscCall(
      ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(rows.size()), rows.data(), PETSC_USE_POINTER, &row_set));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, columns, 0, 1, &all_columns));
  Mat* pieces = nullptr;
  PetscCall(MatCreateSubMatrices(P, 1, &row_set, &all_columns, MAT_INITIAL_MATRIX, &pieces));
  std::vector<Eigen::Triplet<double>> entries;
  for (PetscInt i = 0; i < static_cast<PetscInt>(rows.size()); ++i) {
    PetscInt n = 0;
    const PetscInt* cols = nullptr;
    const PetscScalar* values = nullptr;
    PetscCall(MatGetRow(pieces[0], i, &n, &cols, &values));
    for (PetscInt k = 0; k < n; ++k)
      if (values[k] != 0) entries.emplace_back(static_cast<int>(i), static_cast<int>(cols[k]), values[k]);
    PetscCall(MatRestoreRow(pieces[0], i, &n, &cols, &values));
  }
  out.resize(static_cast<Eigen::Index>(rows.size()), columns);
  out.setFromTriplets(entries.begin(), entries.end());
  PetscCall(MatDestroySubMatrices(1, &pieces));
  PetscCall(ISDestroy(&row_set));
  PetscCall(ISDestroy(&all_columns));
  PetscFunctionReturn(0);
}

// The change one level down: Pᵀ Δ P, from the rows of P that Δ touches. Collective.
PetscErrorCode galerkin_change(Mat P, const std::vector<Entry>& change, std::vector<Entry>& coarse) {
  PetscFunctionBeginUser;
  std::vector<PetscInt> rows;
  rows.reserve(2 * change.size());
  for (const Entry& e : change) {
    rows.push_back(e.row);
    rows.push_back(e.column);
  }
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  std::unordered_map<PetscInt, int> index;
  index.reserve(2 * rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) index[rows[k]] = static_cast<int>(k);
  Eigen::SparseMatrix<double, Eigen::RowMajor> P_rows;
  PetscCall(rows_of(P, rows, P_rows));
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(change.size());
  for (const Entry& e : change) triplets.emplace_back(index[e.row], index[e.column], e.value);
  Eigen::SparseMatrix<double> delta(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(rows.size()));
  delta.setFromTriplets(triplets.begin(), triplets.end());
  const Eigen::SparseMatrix<double> P_local = P_rows;
  const Eigen::SparseMatrix<double> P_transposed = P_local.transpose();
  Eigen::SparseMatrix<double> product = P_transposed * (delta * P_local);
  product.prune(0.0);
  coarse.clear();
  coarse.reserve(product.nonZeros());
  for (int k = 0; k < product.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(product, k); it; ++it)
      coarse.push_back({static_cast<PetscInt>(it.row()), static_cast<PetscInt>(it.col()), it.value()});
  PetscFunctionReturn(0);
}

// Adds every rank's part into M (entries inside its pattern: the changes of a Galerkin
// product never leave the pattern of the product). Collective.
PetscErrorCode add_into(Mat M, const std::vector<Entry>& change) {
  PetscFunctionBeginUser;
  for (const Entry& e : change) PetscCall(MatSetValues(M, 1, &e.row, 1, &e.column, &e.value, ADD_VALUES));
  PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode TruncatedHierarchy::collect(PC pc, Mat A) {
  PetscFunctionBeginUser;
  A_ = A;
  PetscCall(MatGetOwnershipRange(A, &first_, &end_));
  free_.assign(end_ - first_, 1);
  transfers_.clear();
  operators_.clear();
  smoothers_.clear();
  PetscBool is_mg = PETSC_FALSE;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCMG, &is_mg));
  PC amg = pc;
  if (is_mg) {
    // set_up_multigrid()'s P1 level: the P2 → P1 transfer, PᵀAP solved by an AMG.
    PetscInt levels = 0;
    PetscCall(PCMGGetLevels(pc, &levels));
    KSP coarse = nullptr;
    PetscCall(PCMGGetCoarseSolve(pc, &coarse));
    PetscCall(KSPGetPC(coarse, &amg));
    if (levels != 2 || !is_galerkin_amg(amg)) PetscFunctionReturn(0);
    Mat P = nullptr, P1_operator = nullptr;
    PetscCall(PCMGGetInterpolation(pc, 1, &P));
    PetscCall(KSPGetOperators(coarse, nullptr, &P1_operator));
    transfers_.push_back(P);
    operators_.push_back(P1_operator);
    // The AMG was set up on PᵀAP; changed in place it must not be set up again.
    PetscCall(KSPSetReusePreconditioner(coarse, PETSC_TRUE));
  } else if (!is_galerkin_amg(pc)) {
    PetscFunctionReturn(0);
  }
  PetscInt levels = 0;
  PetscCall(PCMGGetLevels(amg, &levels));
  if (is_mg) {
    KSP finest = nullptr;
    PetscCall(PCMGGetSmoother(amg, levels - 1, &finest));
    smoothers_.push_back(finest);
  }
  for (PetscInt level = levels - 1; level >= 1; --level) {
    Mat interpolation = nullptr, op = nullptr;
    KSP smoother = nullptr;
    PetscCall(PCMGGetInterpolation(amg, level, &interpolation));
    PetscCall(PCMGGetSmoother(amg, level - 1, &smoother));
    PetscCall(KSPGetOperators(smoother, nullptr, &op));
    transfers_.push_back(interpolation);
    operators_.push_back(op);
    smoothers_.push_back(smoother);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode TruncatedHierarchy::fix_rows(const std::vector<PetscInt>& fixed) {
  PetscFunctionBeginUser;
  if (!active()) PetscFunctionReturn(0);
  Stopwatch clock;
  const PetscInt n_local = end_ - first_;
  std::vector<char> free_now(n_local, 1);
  for (PetscInt i : fixed) free_now[i] = 0;
  std::vector<PetscInt> changed;
  for (PetscInt i = 0; i < n_local; ++i)
    if (free_now[i] != free_[i]) changed.push_back(i);
  long long n_changed = static_cast<long long>(changed.size());
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &n_changed, 1, MPI_LONG_LONG, MPI_SUM, PetscObjectComm((PetscObject)A_)));
  if (n_changed == 0) PetscFunctionReturn(0);

  // The status (bit 0: free before, bit 1: free now) of every column of the changed rows; the
  // other ranks' by a scatter of the few columns needed.
  std::vector<PetscInt> remote_columns;
  for (PetscInt i : changed) {
    PetscInt n = 0;
    const PetscInt* cols = nullptr;
    PetscCall(MatGetRow(A_, first_ + i, &n, &cols, nullptr));
    for (PetscInt k = 0; k < n; ++k)
      if (cols[k] < first_ || cols[k] >= end_) remote_columns.push_back(cols[k]);
    PetscCall(MatRestoreRow(A_, first_ + i, &n, &cols, nullptr));
  }
  std::sort(remote_columns.begin(), remote_columns.end());
  remote_columns.erase(std::unique(remote_columns.begin(), remote_columns.end()), remote_columns.end());
  std::unordered_map<PetscInt, int> remote_status;
  {
    Vec status = nullptr, gathered = nullptr;
    IS from = nullptr;
    VecScatter scatter = nullptr;
    PetscCall(MatCreateVecs(A_, nullptr, &status));
    PetscScalar* values = nullptr;
    PetscCall(VecGetArray(status, &values));
    for (PetscInt i = 0; i < n_local; ++i) values[i] = (free_[i] ? 1 : 0) + (free_now[i] ? 2 : 0);
    PetscCall(VecRestoreArray(status, &values));
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(remote_columns.size()), remote_columns.data(),
                              PETSC_USE_POINTER, &from));
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(remote_columns.size()), &gathered));
    PetscCall(VecScatterCreate(status, from, gathered, nullptr, &scatter));
    PetscCall(VecScatterBegin(scatter, status, gathered, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(scatter, status, gathered, INSERT_VALUES, SCATTER_FORWARD));
    const PetscScalar* read = nullptr;
    PetscCall(VecGetArrayRead(gathered, &read));
    for (std::size_t k = 0; k < remote_columns.size(); ++k)
      remote_status[remote_columns[k]] = static_cast<int>(read[k]);
    PetscCall(VecRestoreArrayRead(gathered, &read));
    PetscCall(VecScatterDestroy(&scatter));
    PetscCall(VecDestroy(&gathered));
    PetscCall(VecDestroy(&status));
    PetscCall(ISDestroy(&from));
  }
  auto status_of = [&](PetscInt column) {
    if (column >= first_ && column < end_)
      return (free_[column - first_] ? 1 : 0) + (free_now[column - first_] ? 2 : 0);
    return remote_status[column];
  };

  // ΔW: W keeps the entry (i, j), i ≠ j, of A while both rows are free; the diagonal stays.
  // A pair of rows that both changed is counted once, by its smaller row.
  std::vector<Entry> change;
  for (PetscInt i : changed) {
    const PetscInt row = first_ + i;
    PetscInt n = 0;
    const PetscInt* cols = nullptr;
    const PetscScalar* values = nullptr;
    PetscCall(MatGetRow(A_, row, &n, &cols, &values));
    for (PetscInt k = 0; k < n; ++k) {
      const PetscInt column = cols[k];
      if (column == row) continue;
      const int status = status_of(column);
      const bool column_was_free = status & 1, column_is_free = status & 2;
      if (column_was_free != column_is_free && column < row) continue;
      const double weight =
          static_cast<double>(free_now[i] && column_is_free) - static_cast<double>(free_[i] && column_was_free);
      if (weight == 0) continue;
      change.push_back({row, column, weight * values[k]});
      change.push_back({column, row, weight * values[k]});
    }
    PetscCall(MatRestoreRow(A_, row, &n, &cols, &values));
  }
  for (std::size_t level = 0; level < transfers_.size(); ++level) {
    std::vector<Entry> coarse;
    PetscCall(galerkin_change(transfers_[level], change, coarse));
    PetscCall(add_into(operators_[level], coarse));
    change.swap(coarse);
  }
  // Each level's solver re-reads its operator: Jacobi's diagonal, Chebyshev's eigenvalue
  // estimates (the operator's state changed), the coarsest level's factorisation.
  for (KSP smoother : smoothers_) {
    Mat op = nullptr, preconditioning = nullptr;
    PetscCall(KSPGetOperators(smoother, &op, &preconditioning));
    PetscCall(PetscObjectReference(reinterpret_cast<PetscObject>(op)));
    PetscCall(PetscObjectReference(reinterpret_cast<PetscObject>(preconditioning)));
    PetscCall(KSPSetOperators(smoother, op, preconditioning));
    PetscCall(MatDestroy(&op));
    PetscCall(MatDestroy(&preconditioning));
  }
  free_ = free_now;
  update_seconds_ += clock.seconds();
  PetscFunctionReturn(0);
}

}  // namespace contactqp::detail
