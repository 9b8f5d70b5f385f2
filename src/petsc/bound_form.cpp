// make_bound_form() (bound_form.hpp): the per-group change of variables.
#include "bound_form.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <numeric>

namespace contactqp::detail {
namespace {

int find(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

bool make_bound_form(const QuadraticProgram& qp, const MatrixLayout& layout, BoundForm& form, std::string& message) {
  const int n = qp.n_dofs(), m = qp.n_constraints();
  // Rows that share a column belong to one group (union-find over B's columns).
  std::vector<int> parent(m);
  std::iota(parent.begin(), parent.end(), 0);
  for (int j = 0; j < qp.B.outerSize(); ++j) {
    int first = -1;
    for (SparseMatrix::InnerIterator it(qp.B, j); it; ++it) {
      if (it.value() == 0) continue;
      if (first < 0)
        first = find(parent, static_cast<int>(it.row()));
      else
        parent[find(parent, static_cast<int>(it.row()))] = first;
    }
  }
  std::vector<std::vector<int>> rows_of(m), columns_of(m);
  for (int i = 0; i < m; ++i) rows_of[find(parent, i)].push_back(i);
  for (int j = 0; j < qp.B.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(qp.B, j); it; ++it)
      if (it.value() != 0) {
        std::vector<int>& columns = columns_of[find(parent, static_cast<int>(it.row()))];
        if (columns.empty() || columns.back() != j) columns.push_back(j);
      }
  const Eigen::SparseMatrix<double, Eigen::RowMajor> B_rows = qp.B;

  std::vector<Eigen::Triplet<double>> Q, Q_inverse;
  std::vector<char> in_group(n, 0);
  // The P1 level (quadratic elements): column c of a free vertex DOF d is column_of_dof[d].
  // A group all of whose DOFs are vertex DOFs gets its change of variables on those columns
  // too (Q_c, a block of Q), so that the candidate vertex's coarse columns are its variables.
  const CoarseSpace& coarse = qp.coarse_space;
  const int n_coarse = coarse.empty() ? 0 : static_cast<int>(coarse.interpolation.cols());
  std::vector<int> column_of_dof(n_coarse ? n : 0, -1);
  for (int c = 0; c < n_coarse; ++c)
    if (coarse.column_dof[c] >= 0) column_of_dof[coarse.column_dof[c]] = c;
  std::vector<Eigen::Triplet<double>> Q_coarse, Q_coarse_inverse;
  std::vector<char> coarse_in_group(n_coarse, 0);
  BoundQp& problem = form.problem;
  problem.bounded.assign(m, -1);
  problem.upper = qp.g;
  for (int root = 0; root < m; ++root) {
    const std::vector<int>& rows = rows_of[root];
    const std::vector<int>& columns = columns_of[root];
    if (rows.empty()) continue;
    const int r = static_cast<int>(rows.size()), c = static_cast<int>(columns.size());
    Eigen::MatrixXd block = Eigen::MatrixXd::Zero(r, c);
    for (int a = 0; a < r; ++a)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(B_rows, rows[a]); it; ++it) {
        const int b = static_cast<int>(std::lower_bound(columns.begin(), columns.end(), it.col()) - columns.begin());
        block(a, b) = it.value();
      }
    const std::string dependent =
        "the contact rows of node group starting at row " + std::to_string(rows[0]) + " (" + std::to_string(r) +
        " rows on " + std::to_string(c) +
        " DOFs) are linearly dependent; the petsc backend needs independent rows at each node";
    // More rows than DOFs are dependent: refused before T, which holds c rows, is filled.
    if (r > c) {
      message = dependent;
      return false;
    }
    // T = [rows of B; an orthonormal basis of the complement of their span].
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(block.transpose());
    const Eigen::MatrixXd basis = qr.householderQ();  // c × c, orthogonal
    Eigen::MatrixXd T(c, c);
    T.topRows(r) = block;
    if (c > r) T.bottomRows(c - r) = basis.rightCols(c - r).transpose();
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(T);
    // |det T| ≤ the product of its row lengths (Hadamard), with equality for orthogonal rows:
    // their ratio measures how far the rows are from dependent.
    if (lu.rank() < c || std::abs(lu.determinant()) < 1e-8 * T.rowwise().norm().prod()) {
      message = dependent;
      return false;
    }
    const Eigen::MatrixXd inverse = lu.inverse();
    for (int a = 0; a < c; ++a) {
      in_group[columns[a]] = 1;
      for (int b = 0; b < c; ++b) {
        if (inverse(a, b) != 0) Q.emplace_back(columns[a], columns[b], inverse(a, b));
        if (T(a, b) != 0) Q_inverse.emplace_back(columns[a], columns[b], T(a, b));
      }
    }
    for (int a = 0; a < r; ++a) problem.bounded[rows[a]] = columns[a];
    if (n_coarse && std::all_of(columns.begin(), columns.end(), [&](int j) { return column_of_dof[j] >= 0; }))
      for (int a = 0; a < c; ++a) {
        coarse_in_group[column_of_dof[columns[a]]] = 1;
        for (int b = 0; b < c; ++b) {
          if (inverse(a, b) != 0)
            Q_coarse.emplace_back(column_of_dof[columns[a]], column_of_dof[columns[b]], inverse(a, b));
          if (T(a, b) != 0)
            Q_coarse_inverse.emplace_back(column_of_dof[columns[a]], column_of_dof[columns[b]], T(a, b));
        }
      }
  }
  for (int j = 0; j < n; ++j)
    if (!in_group[j]) {
      Q.emplace_back(j, j, 1.0);
      Q_inverse.emplace_back(j, j, 1.0);
    }
  form.Q.resize(n, n);
  form.Q.setFromTriplets(Q.begin(), Q.end());
  SparseMatrix Q_inv(n, n);
  Q_inv.setFromTriplets(Q_inverse.begin(), Q_inverse.end());

  const SparseMatrix QT = form.Q.transpose();
  const SparseMatrix A = QT * qp.K * form.Q;
  problem.A = 0.5 * (A + SparseMatrix(A.transpose()));  // exactly symmetric, for CG and MAT_SYMMETRIC
  problem.A.prune(0.0);
  problem.A_is_rank_share = layout.share;            // QᵀK_rQ sums to QᵀKQ: Q is the same on every rank
  problem.distributed_row = layout.distributed_row;  // v is indexed like u
  problem.b = QT * qp.f;
  if (qp.near_null_space.rows() == n) problem.near_null_space = Q_inv * qp.near_null_space;
  if (n_coarse) {
    for (int c = 0; c < n_coarse; ++c)
      if (!coarse_in_group[c]) {
        Q_coarse.emplace_back(c, c, 1.0);
        Q_coarse_inverse.emplace_back(c, c, 1.0);
      }
    SparseMatrix Q_c(n_coarse, n_coarse), Q_c_inverse(n_coarse, n_coarse);
    Q_c.setFromTriplets(Q_coarse.begin(), Q_coarse.end());
    Q_c_inverse.setFromTriplets(Q_coarse_inverse.begin(), Q_coarse_inverse.end());
    problem.coarse_interpolation = Q_inv * coarse.interpolation * Q_c;
    problem.coarse_interpolation.prune(0.0);
    if (coarse.near_null_space.rows() == n_coarse)
      problem.coarse_near_null_space = Q_c_inverse * coarse.near_null_space;
    problem.coarse_vertex = coarse.column_vertex;
    problem.coarse_row = coarse.column_dof;  // v is indexed like u
    problem.coarse_block_size = coarse.block_size;
    problem.coarse_bounded.assign(m, -1);
    for (int i = 0; i < m; ++i) {
      const int column = problem.bounded[i] >= 0 ? column_of_dof[problem.bounded[i]] : -1;
      if (column >= 0 && coarse_in_group[column]) problem.coarse_bounded[i] = column;
    }
  }
  return true;
}

}  // namespace contactqp::detail
