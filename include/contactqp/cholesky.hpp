// Sparse Cholesky factorisation of a symmetric positive definite matrix, with CHOLMOD.
//
// Keeps Eigen's shape: analyse the pattern and factorise once, then solve many times and ask
// info(). CHOLMOD stays behind this header (pimpl): nothing public includes <cholmod.h>.
// One implementation of LinearSolver (linear_solver.hpp), the one every backend uses by default.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>

#include "contactqp/linear_solver.hpp"

namespace contactqp {

// What CHOLMOD's symbolic analysis predicts for the factor of A, before any memory for it is
// committed: for sizing a problem (benchmarks/scaling: where the direct solver stops fitting).
struct FactorPrediction {
  bool ok = false;
  std::string message;   // why not, when !ok
  std::string ordering;  // the ordering the analysis chose: "amd", "metis", ...
  bool supernodal = false;
  long long factor_nonzeros = 0;    // nnz(L)
  double factor_bytes = 0;          // what factorising allocates for L (values and pattern)
  bool fits_32bit_indices = false;  // CholeskyFactor (CHOLMOD's 32-bit interface) holds at most 2^31 - 1 entries
  double flops = 0;                 // floating-point operations of the factorisation
  double analyse_seconds = 0;
};

class CholeskyFactor : public LinearSolver {
 public:
  // Analyses and factorises A (only its lower triangle is read). Never throws on a
  // numerical failure: check ok() and message(). `A` is not referenced after construction.
  explicit CholeskyFactor(const Eigen::SparseMatrix<double>& A, Ordering ordering = Ordering::Auto);
  ~CholeskyFactor() override;
  CholeskyFactor(const CholeskyFactor&) = delete;
  CholeskyFactor& operator=(const CholeskyFactor&) = delete;

  bool ok() const override;
  // Empty when ok(); otherwise e.g. "not positive definite: pivot 12 of 410 is not positive".
  const std::string& message() const override;
  int size() const override;
  // Index (in A's numbering) of the first non-positive pivot when factorisation failed, else -1.
  int failed_column() const;

  // x = (scale·A)⁻¹ b. Not thread-safe: CHOLMOD's workspace is shared.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const override;
  using LinearSolver::solve;  // the warm-started form: a direct solve ignores the guess
  Eigen::MatrixXd solve_columns(const Eigen::MatrixXd& b) const override;  // all columns at once

  // With P A Pᵀ = L Lᵀ and W = L⁻¹ P Cᵀ: S = C A⁻¹ Cᵀ = WᵀW and c = C A⁻¹ b = Wᵀ(L⁻¹ P b),
  // for a sparse C (m × n) whose rows have few entries. Column j of W is nonzero only on the
  // elimination-tree path from C's row j to the root, so W is computed by a forward solve
  // restricted to the union of those paths (dense blocks per supernode, freed as soon as
  // their contributions are passed up) and S accumulated block by block: far less than m
  // solves. Costs one forward solve for c. Not thread-safe, like solve().
  Condensation condense(const Eigen::SparseMatrix<double>& C, const Eigen::VectorXd& b) const override;

  // The same factor, standing for the matrix c·A (solves divide by c). Shares the storage.
  std::shared_ptr<const CholeskyFactor> scaled(double c) const;
  LinearSolverStatistics statistics() const override;

  // The symbolic analysis alone (no numeric factorisation): nnz(L), its bytes and the flops.
  static FactorPrediction predict(const Eigen::SparseMatrix<double>& A, Ordering ordering = Ordering::Auto);

  double analyse_seconds() const;
  double factorize_seconds() const;
  long long factor_nonzeros() const;  // nnz(L), a measure of memory and solve cost
  bool supernodal() const;
  std::string ordering_name() const override;  // the ordering CHOLMOD used: "amd", "metis", ...

 protected:
  std::shared_ptr<const LinearSolver> scaled_solver(double c) const override { return scaled(c); }

 private:
  struct Impl;
  CholeskyFactor(std::shared_ptr<Impl> impl, double scale);
  std::shared_ptr<Impl> impl_;
  double scale_ = 1.0;
};

}  // namespace contactqp
