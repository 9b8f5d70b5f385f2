// make_bound_form() (bound_form.hpp): the per-group change of variables.
#include "bound_form.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "qp/friction_sets.hpp"

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

bool make_bound_form(const QuadraticProgram& qp, const MatrixLayout& layout, BoundForm& form, std::string& message,
                     bool with_operator) {
  const int n = qp.n_dofs(), m = qp.n_constraints();
  // The rows that become variables: B's, then with friction T's (row m + i·nd + k is contact
  // row i's k-th tangential direction). A block is one contact row's rows: its normal row and,
  // with friction, its tangential rows, which touch the same DOFs.
  const bool friction = !qp.friction.empty() && !without_friction_force(qp.friction);
  const int nd = friction ? qp.friction.n_directions : 0;
  const int M = m * (1 + nd);
  SparseMatrix C_columns = qp.B;
  if (friction) {
    std::vector<Eigen::Triplet<double>> entries;
    for (int j = 0; j < qp.B.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(qp.B, j); it; ++it)
        entries.emplace_back(static_cast<int>(it.row()), j, it.value());
    for (int j = 0; j < qp.friction.T.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(qp.friction.T, j); it; ++it)
        entries.emplace_back(m + static_cast<int>(it.row()), j, it.value());
    C_columns.resize(M, n);
    C_columns.setFromTriplets(entries.begin(), entries.end());
  }
  // Round-off is no coefficient. A tangent of a node on a symmetry plane, along the plane's
  // prescribed direction, left 1e-32 on the node's free DOFs (mindlin-spheres.json at 7.8e5
  // DOFs): a row of nothing but round-off, with no DOF of its own to pivot on, sent the whole
  // contact zone (14 553 rows on 29 358 DOFs) to one dense change of variables, whose QR had not
  // ended after 10 minutes and 8.4 GB per rank (and whose rows would then have been refused as
  // dependent, as a small case is: tests/unit/test_bound_form.cpp). The rows' coefficients are
  // unit vectors times interpolation weights, O(1): what is 1e-12 of the largest is dropped (it
  // moves the rows by less than any tolerance a solve can reach), and such a row has no variable.
  double largest = 0;
  for (int j = 0; j < C_columns.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(C_columns, j); it; ++it) largest = std::max(largest, std::abs(it.value()));
  C_columns.prune(largest, 1e-12);
  const auto block_of = [m, nd](int row) { return row < m ? row : (row - m) / nd; };
  // Rows that share a column belong to one group (union-find over C's columns).
  std::vector<int> parent(M);
  std::iota(parent.begin(), parent.end(), 0);
  for (int j = 0; j < C_columns.outerSize(); ++j) {
    int first = -1;
    for (SparseMatrix::InnerIterator it(C_columns, j); it; ++it) {
      if (it.value() == 0) continue;
      if (first < 0)
        first = find(parent, static_cast<int>(it.row()));
      else
        parent[find(parent, static_cast<int>(it.row()))] = first;
    }
  }
  std::vector<std::vector<int>> rows_of(M), columns_of(M);
  // A tangential row without a free DOF (a node on a symmetry plane, its direction across the
  // plane prescribed) has no variable: its slip is 0 whatever u, and its λ_T stays 0.
  std::vector<char> empty_row(M, 1);
  for (int j = 0; j < C_columns.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(C_columns, j); it; ++it)
      if (it.value() != 0) empty_row[it.row()] = 0;
  for (int i = 0; i < M; ++i)
    if (i < m || !empty_row[i]) rows_of[find(parent, i)].push_back(i);
  for (int j = 0; j < C_columns.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(C_columns, j); it; ++it)
      if (it.value() != 0) {
        std::vector<int>& columns = columns_of[find(parent, static_cast<int>(it.row()))];
        if (columns.empty() || columns.back() != j) columns.push_back(j);
      }
  const Eigen::SparseMatrix<double, Eigen::RowMajor> C_rows = C_columns;

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
  problem.n_directions = nd;
  problem.tangential.assign(static_cast<std::size_t>(m) * nd, -1);
  // The variable of C's row `row`.
  const auto variable_of = [&](int row) -> int& {
    return row < m ? problem.bounded[row] : problem.tangential[row - m];
  };
  std::vector<int> blocks_at(n, 0), last_block(n, -1);  // how many blocks of the group at hand touch each DOF
  for (int root = 0; root < M; ++root) {
    const std::vector<int>& rows = rows_of[root];
    const std::vector<int>& columns = columns_of[root];
    if (rows.empty()) continue;
    const int r = static_cast<int>(rows.size()), c = static_cast<int>(columns.size());

    // A group of several blocks each with DOFs of its own (a node against another body's face:
    // the node's DOFs are its block's alone, the face's are shared by its neighbours' rows)
    // gets a change of variables per block on its own DOFs, the shared ones kept. One dense T
    // over the group would couple every DOF of a contact zone with every other (the two
    // spheres' 383 rows: one dense block over all their DOFs, 18 s to form and an A of 174 MiB
    // per rank for 51k DOFs).
    std::vector<std::vector<int>> blocks;  // the group's rows, block by block (rows ascend within each)
    {
      std::vector<int> order = rows;
      std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return block_of(a) < block_of(b); });
      for (int row : order) {
        if (blocks.empty() || block_of(blocks.back().front()) != block_of(row)) blocks.emplace_back();
        blocks.back().push_back(row);
      }
    }
    if (blocks.size() > 1) {
      for (std::size_t b = 0; b < blocks.size(); ++b)
        for (int row : blocks[b])
          for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(C_rows, row); it; ++it)
            if (it.value() != 0 && last_block[it.col()] != static_cast<int>(b)) {
              last_block[it.col()] = static_cast<int>(b);
              ++blocks_at[it.col()];
            }
      const int n_blocks = static_cast<int>(blocks.size());
      std::vector<std::vector<int>> own(n_blocks);
      bool each_has_own = true;
      for (int b = 0; b < n_blocks && each_has_own; ++b) {
        for (int row : blocks[b]) {
          double own_norm = 0, norm = 0;
          for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(C_rows, row); it; ++it) {
            if (it.value() == 0) continue;
            norm += it.value() * it.value();
            if (blocks_at[it.col()] == 1) {
              own_norm += it.value() * it.value();
              if (std::find(own[b].begin(), own[b].end(), static_cast<int>(it.col())) == own[b].end())
                own[b].push_back(static_cast<int>(it.col()));
            }
          }
          // Pivoting on a part of the row much shorter than the row would divide by it.
          each_has_own = each_has_own && own_norm > 0 && own_norm >= 0.0625 * norm;
        }
        std::sort(own[b].begin(), own[b].end());
        each_has_own = each_has_own && own[b].size() >= blocks[b].size();
      }
      for (int j : columns) blocks_at[j] = 0, last_block[j] = -1;
      // Block b's rows are P·u_own + S·u_shared (P: k × d). New variables on its own DOFs,
      // v_own = T u_own + [S; 0] u_shared with T = [P; an orthonormal basis of P's complement],
      // so that v_own[a] is the block's row a; the shared DOFs keep theirs (v = u there). Then
      // u_own = T⁻¹ (v_own − [S; 0] v_shared).
      struct Change {
        Eigen::MatrixXd T, inverse, S;
        std::vector<int> shared;
      };
      std::vector<Change> changes(each_has_own ? n_blocks : 0);
      for (int b = 0; b < static_cast<int>(changes.size()) && each_has_own; ++b) {
        Change& change = changes[b];
        const int k = static_cast<int>(blocks[b].size()), d = static_cast<int>(own[b].size());
        for (int row : blocks[b])
          for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(C_rows, row); it; ++it)
            if (it.value() != 0 && !std::binary_search(own[b].begin(), own[b].end(), static_cast<int>(it.col())) &&
                std::find(change.shared.begin(), change.shared.end(), static_cast<int>(it.col())) ==
                    change.shared.end())
              change.shared.push_back(static_cast<int>(it.col()));
        Eigen::MatrixXd P = Eigen::MatrixXd::Zero(k, d);
        change.S = Eigen::MatrixXd::Zero(k, static_cast<Eigen::Index>(change.shared.size()));
        for (int a = 0; a < k; ++a)
          for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(C_rows, blocks[b][a]); it; ++it) {
            if (it.value() == 0) continue;
            const int col = static_cast<int>(it.col());
            const auto at = std::lower_bound(own[b].begin(), own[b].end(), col);
            if (at != own[b].end() && *at == col)
              P(a, at - own[b].begin()) = it.value();
            else
              change.S(a, std::find(change.shared.begin(), change.shared.end(), col) - change.shared.begin()) =
                  it.value();
          }
        change.T = with_complement(P);
        // One row: T's rows are orthogonal, det T = |p|, far from 0. Several (a node's normal
        // and tangential rows): their own parts must be independent, as the dense path checks.
        if (k > 1) {
          const Eigen::FullPivLU<Eigen::MatrixXd> lu(change.T);
          each_has_own = lu.rank() == d && std::abs(lu.determinant()) >= 1e-8 * change.T.rowwise().norm().prod();
        }
        change.inverse = change.T.inverse();
      }
      if (each_has_own) {
        for (int b = 0; b < n_blocks; ++b) {
          const Change& change = changes[b];
          const int k = static_cast<int>(blocks[b].size()), d = static_cast<int>(own[b].size());
          std::vector<int> dofs = own[b];
          dofs.insert(dofs.end(), change.shared.begin(), change.shared.end());
          const bool coarse_too = on_coarse_level(dofs);
          const Eigen::MatrixXd shift = -change.inverse.leftCols(k) * change.S;  // d × shared
          for (int x = 0; x < d; ++x) {
            in_group[own[b][x]] = 1;
            if (coarse_too) coarse_in_group[column_of_dof[own[b][x]]] = 1;
            for (int y = 0; y < d; ++y) put(own[b][x], own[b][y], change.inverse(x, y), change.T(x, y), coarse_too);
            for (std::size_t s = 0; s < change.shared.size(); ++s)
              put(own[b][x], change.shared[s], shift(x, s), x < k ? change.S(x, s) : 0.0, coarse_too);
          }
          for (int a = 0; a < k; ++a) variable_of(blocks[b][a]) = own[b][a];
        }
        continue;
      }
    }

    Eigen::MatrixXd block = Eigen::MatrixXd::Zero(r, c);
    for (int a = 0; a < r; ++a)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(C_rows, rows[a]); it; ++it) {
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
    // T = [rows of C; an orthonormal basis of the complement of their span].
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
    for (int a = 0; a < r; ++a) variable_of(rows[a]) = columns[a];
  }
  if (friction) {
    problem.offset = qp.friction.offset.size() ? qp.friction.offset : Eigen::VectorXd::Zero(problem.tangential.size());
    problem.radius = qp.friction.law == FrictionLaw::Tresca ? qp.friction.threshold : Eigen::VectorXd::Zero(m);
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
  problem.A_is_rank_share = layout.share;            // QᵀK_rQ sums to QᵀKQ: Q is the same on every rank
  problem.distributed_row = layout.distributed_row;  // v is indexed like u
  problem.b = QT * qp.f;
  if (!with_operator) return true;
  const SparseMatrix A = QT * qp.K * form.Q;
  problem.A = 0.5 * (A + SparseMatrix(A.transpose()));  // exactly symmetric, for CG and MAT_SYMMETRIC
  problem.A.prune(0.0);
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
