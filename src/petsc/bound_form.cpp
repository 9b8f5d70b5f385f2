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

// [rows; an orthonormal basis of the complement of their span] (square: rows.cols() rows).
Eigen::MatrixXd with_complement(const Eigen::MatrixXd& rows) {
  const Eigen::Index r = rows.rows(), c = rows.cols();
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(rows.transpose());
  const Eigen::MatrixXd basis = qr.householderQ();  // c × c, orthogonal
  Eigen::MatrixXd T(c, c);
  T.topRows(r) = rows;
  if (c > r) T.bottomRows(c - r) = basis.rightCols(c - r).transpose();
  return T;
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
  // A change of variables all of whose DOFs are vertex DOFs is made on those columns too (Q_c, a
  // block of Q), so that the candidate vertex's coarse columns are its variables.
  const CoarseSpace& coarse = qp.coarse_space;
  const int n_coarse = coarse.empty() ? 0 : static_cast<int>(coarse.interpolation.cols());
  std::vector<int> column_of_dof(n_coarse ? n : 0, -1);
  for (int c = 0; c < n_coarse; ++c)
    if (coarse.column_dof[c] >= 0) column_of_dof[coarse.column_dof[c]] = c;
  std::vector<Eigen::Triplet<double>> Q_coarse, Q_coarse_inverse;
  std::vector<char> coarse_in_group(n_coarse, 0);
  const auto on_coarse_level = [&](const std::vector<int>& dofs) {
    return n_coarse && std::all_of(dofs.begin(), dofs.end(), [&](int j) { return column_of_dof[j] >= 0; });
  };
  // Entry (i, j) of Q and of Q⁻¹, and of their coarse blocks when `coarse_too`.
  const auto put = [&](int i, int j, double q, double q_inverse, bool coarse_too) {
    if (q != 0) Q.emplace_back(i, j, q);
    if (q_inverse != 0) Q_inverse.emplace_back(i, j, q_inverse);
    if (!coarse_too) return;
    if (q != 0) Q_coarse.emplace_back(column_of_dof[i], column_of_dof[j], q);
    if (q_inverse != 0) Q_coarse_inverse.emplace_back(column_of_dof[i], column_of_dof[j], q_inverse);
  };
  BoundQp& problem = form.problem;
  problem.bounded.assign(m, -1);
  problem.upper = qp.g;
  std::vector<int> rows_at(n, 0);  // how many rows of the group at hand touch each DOF
  for (int root = 0; root < m; ++root) {
    const std::vector<int>& rows = rows_of[root];
    const std::vector<int>& columns = columns_of[root];
    if (rows.empty()) continue;
    const int r = static_cast<int>(rows.size()), c = static_cast<int>(columns.size());

    // A group of several rows each with DOFs of its own (a node against another body's face:
    // the node's DOFs are its row's alone, the face's are shared by its neighbours' rows) gets
    // a change of variables per row on its own DOFs, the shared ones kept. One dense T over the
    // group would couple every DOF of a contact zone with every other (the two spheres' 383
    // rows: one dense block over all their DOFs, 18 s to form and an A of 174 MiB per rank for 51k DOFs).
    if (r > 1) {
      for (int row : rows)
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(B_rows, row); it; ++it)
          if (it.value() != 0) ++rows_at[it.col()];
      std::vector<std::vector<int>> own(r);
      bool each_has_own = true;
      for (int a = 0; a < r && each_has_own; ++a) {
        double own_norm = 0, norm = 0;
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(B_rows, rows[a]); it; ++it) {
          if (it.value() == 0) continue;
          norm += it.value() * it.value();
          if (rows_at[it.col()] == 1) {
            own[a].push_back(static_cast<int>(it.col()));
            own_norm += it.value() * it.value();
          }
        }
        // Pivoting on a part of the row much shorter than the row would divide by it.
        each_has_own = !own[a].empty() && own_norm >= 0.0625 * norm;
      }
      for (int j : columns) rows_at[j] = 0;
      if (each_has_own) {
        // Row a is p·u_own + s·u_shared. New variables on its own DOFs, v_own = T u_own + e₁ s·u_shared
        // with T = [p; an orthonormal basis of p's complement], so v_own[0] is the row; the shared
        // DOFs keep theirs (v = u there). Then u_own = T⁻¹ (v_own − e₁ s·v_shared).
        for (int a = 0; a < r; ++a) {
          std::vector<int> shared;
          std::vector<double> p, s;
          for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(B_rows, rows[a]); it; ++it) {
            if (it.value() == 0) continue;
            const bool is_own = std::binary_search(own[a].begin(), own[a].end(), static_cast<int>(it.col()));
            if (!is_own) shared.push_back(static_cast<int>(it.col()));
            (is_own ? p : s).push_back(it.value());
          }
          const int d = static_cast<int>(own[a].size());
          const Eigen::MatrixXd T = with_complement(Eigen::Map<const Eigen::MatrixXd>(p.data(), 1, d));
          const Eigen::MatrixXd inverse = T.inverse();  // T's rows are orthogonal: det T = |p|, far from 0
          std::vector<int> dofs = own[a];
          dofs.insert(dofs.end(), shared.begin(), shared.end());
          const bool coarse_too = on_coarse_level(dofs);
          for (int x = 0; x < d; ++x) {
            in_group[own[a][x]] = 1;
            if (coarse_too) coarse_in_group[column_of_dof[own[a][x]]] = 1;
            for (int y = 0; y < d; ++y) put(own[a][x], own[a][y], inverse(x, y), T(x, y), coarse_too);
            for (std::size_t k = 0; k < shared.size(); ++k)
              put(own[a][x], shared[k], -inverse(x, 0) * s[k], x == 0 ? s[k] : 0.0, coarse_too);
          }
          problem.bounded[rows[a]] = own[a][0];
        }
        continue;
      }
    }

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
    const Eigen::MatrixXd T = with_complement(block);
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(T);
    // |det T| ≤ the product of its row lengths (Hadamard), with equality for orthogonal rows:
    // their ratio measures how far the rows are from dependent.
    if (lu.rank() < c || std::abs(lu.determinant()) < 1e-8 * T.rowwise().norm().prod()) {
      message = dependent;
      return false;
    }
    const Eigen::MatrixXd inverse = lu.inverse();
    const bool coarse_too = on_coarse_level(columns);
    for (int a = 0; a < c; ++a) {
      in_group[columns[a]] = 1;
      if (coarse_too) coarse_in_group[column_of_dof[columns[a]]] = 1;
      for (int b = 0; b < c; ++b) put(columns[a], columns[b], inverse(a, b), T(a, b), coarse_too);
    }
    for (int a = 0; a < r; ++a) problem.bounded[rows[a]] = columns[a];
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
