// Non-negative least squares, min ‖A x − b‖₂ subject to x ≥ 0, by Lawson and Hanson's active-set
// method (Solving Least Squares Problems, 1974, ch. 23): the evidence of a QP without solution
// (no_solution.hpp) is the residual of one. Exact up to round-off after finitely many steps,
// which an iterative method would not be; no Debian package offers it in C++ (Eigen 3.4.0 has
// no NNLS module). Meant for A with few positive entries at the solution: each step solves the
// normal equations of the passive columns, dense.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace contactqp::detail {

struct NnlsResult {
  Eigen::VectorXd x;         // ≥ 0
  Eigen::VectorXd residual;  // b − A x
  bool converged = false;    // the optimality test held before max_steps
  int steps = 0;
};

// A: rows × m, sparse (its columns are the candidates). Stops when no column outside the passive
// set has a positive gradient above tol·‖Aᵀb‖∞ (relative), or after max_steps column additions.
NnlsResult nnls(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b, double tol, int max_steps);

}  // namespace contactqp::detail
