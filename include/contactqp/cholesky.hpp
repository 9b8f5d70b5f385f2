// Sparse Cholesky factorisation of a symmetric positive definite matrix, with CHOLMOD.
//
// Keeps Eigen's shape: analyse the pattern and factorise once, then solve many times and ask
// info(). CHOLMOD stays behind this header (pimpl): nothing public includes <cholmod.h>.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>

namespace contactqp {

class CholeskyFactor {
 public:
  // Analyses and factorises A (only its lower triangle is read). Never throws on a
  // numerical failure: check ok() and message(). `A` is not referenced after construction.
  explicit CholeskyFactor(const Eigen::SparseMatrix<double>& A);
  ~CholeskyFactor();
  CholeskyFactor(const CholeskyFactor&) = delete;
  CholeskyFactor& operator=(const CholeskyFactor&) = delete;

  bool ok() const;
  // Empty when ok(); otherwise e.g. "not positive definite: pivot 12 of 410 is not positive".
  const std::string& message() const;
  int size() const;
  // Index (in A's numbering) of the first non-positive pivot when factorisation failed, else -1.
  int failed_column() const;

  // x = (scale·A)⁻¹ b. Not thread-safe: CHOLMOD's workspace is shared.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  Eigen::MatrixXd solve_columns(const Eigen::MatrixXd& b) const;  // one solve per column

  // The same factor, standing for the matrix c·A (solves divide by c). Shares the storage.
  std::shared_ptr<const CholeskyFactor> scaled(double c) const;

  double analyse_seconds() const;
  double factorize_seconds() const;
  long long factor_nonzeros() const;  // nnz(L), a measure of memory and solve cost

 private:
  struct Impl;
  CholeskyFactor(std::shared_ptr<Impl> impl, double scale);
  std::shared_ptr<Impl> impl_;
  double scale_ = 1.0;
};

}  // namespace contactqp
