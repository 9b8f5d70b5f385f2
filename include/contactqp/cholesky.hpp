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

// The fill-reducing ordering CHOLMOD analyses with. Measured on the Hertz meshes up to 1.1e6
// DOFs (docs/scaling.md, "Orderings"), AMD gives the fastest analyse + factorise + solve (or within noise),
// so SolveOptions defaults to it; METIS needs about 30% less memory for L at 1e6 DOFs.
enum class Ordering {
  Auto,   // CHOLMOD's default: AMD, and METIS as well when AMD's fill is high; the better one wins
  Amd,    // approximate minimum degree only: the cheapest analysis
  Metis,  // METIS nested dissection only: less fill and flops on large 2D meshes, slower analysis
};

std::string to_string(Ordering ordering);  // "auto", "amd", "metis"
// "amd" -> Ordering::Amd. Unknown names throw InputError(field, "... valid: auto, amd, metis").
Ordering parse_ordering(const std::string& name, const std::string& field);

// C A⁻¹ Cᵀ and C A⁻¹ b for a sparse C with few rows: the condensed operator of contact rows.
struct Condensation {
  Eigen::MatrixXd S;             // C A⁻¹ Cᵀ (m × m), symmetric positive semidefinite
  Eigen::VectorXd c;             // C A⁻¹ b (m)
  long long reached_columns = 0; // columns of L on the elimination-tree paths of C's rows
  long long entries = 0;         // entries of W = L⁻¹ P Cᵀ computed (dense blocks per supernode)
  long long peak_entries = 0;    // the most of them held at once
};

class CholeskyFactor {
 public:
  // Analyses and factorises A (only its lower triangle is read). Never throws on a
  // numerical failure: check ok() and message(). `A` is not referenced after construction.
  explicit CholeskyFactor(const Eigen::SparseMatrix<double>& A, Ordering ordering = Ordering::Auto);
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

  // With P A Pᵀ = L Lᵀ and W = L⁻¹ P Cᵀ: S = C A⁻¹ Cᵀ = WᵀW and c = C A⁻¹ b = Wᵀ(L⁻¹ P b),
  // for a sparse C (m × n) whose rows have few entries. Column j of W is nonzero only on the
  // elimination-tree path from C's row j to the root, so W is computed by a forward solve
  // restricted to the union of those paths (dense blocks per supernode, freed as soon as
  // their contributions are passed up) and S accumulated block by block: far less than m
  // solves. Costs one forward solve for c. Not thread-safe, like solve().
  Condensation condense(const Eigen::SparseMatrix<double>& C, const Eigen::VectorXd& b) const;

  // The same factor, standing for the matrix c·A (solves divide by c). Shares the storage.
  std::shared_ptr<const CholeskyFactor> scaled(double c) const;

  double analyse_seconds() const;
  double factorize_seconds() const;
  long long factor_nonzeros() const;  // nnz(L), a measure of memory and solve cost
  bool supernodal() const;
  std::string ordering_name() const;  // the ordering CHOLMOD used: "amd", "metis", ...

 private:
  struct Impl;
  CholeskyFactor(std::shared_ptr<Impl> impl, double scale);
  std::shared_ptr<Impl> impl_;
  double scale_ = 1.0;
};

}  // namespace contactqp
