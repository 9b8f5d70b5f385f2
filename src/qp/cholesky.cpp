// CHOLMOD behind the CholeskyFactor interface. Only this file includes <cholmod.h>.
#include "contactqp/cholesky.hpp"

#include <cholmod.h>

#include <mutex>

#include "contactqp/timer.hpp"

namespace contactqp {

struct CholeskyFactor::Impl {
  cholmod_common common;
  cholmod_factor* L = nullptr;
  int n = 0;
  bool ok = false;
  int failed_column = -1;
  std::string message;
  double analyse_seconds = 0, factorize_seconds = 0;
  std::mutex mutex;  // CHOLMOD's workspace lives in `common`: one solve at a time

  Impl() {
    cholmod_start(&common);
    common.print = 0;     // failures are reported through message(), not on stderr
    common.final_ll = 1;  // keep L Lᵀ (not L D Lᵀ) so callers may use triangular solves with L
  }
  ~Impl() {
    if (L) cholmod_free_factor(&L, &common);
    cholmod_finish(&common);
  }

  // A read-only CHOLMOD view of Eigen's compressed column storage: no copy.
  static cholmod_sparse view(const Eigen::SparseMatrix<double>& A) {
    cholmod_sparse s{};
    s.nrow = A.rows();
    s.ncol = A.cols();
    s.nzmax = A.nonZeros();
    s.p = const_cast<int*>(A.outerIndexPtr());
    s.i = const_cast<int*>(A.innerIndexPtr());
    s.x = const_cast<double*>(A.valuePtr());
    s.stype = -1;  // symmetric, lower triangle used: the upper one is never read
    s.itype = CHOLMOD_INT;
    s.xtype = CHOLMOD_REAL;
    s.dtype = CHOLMOD_DOUBLE;
    s.sorted = 1;
    s.packed = 1;
    return s;
  }

  static cholmod_dense view(const Eigen::MatrixXd& b) {
    cholmod_dense d{};
    d.nrow = b.rows();
    d.ncol = b.cols();
    d.nzmax = b.size();
    d.d = b.rows();
    d.x = const_cast<double*>(b.data());
    d.xtype = CHOLMOD_REAL;
    d.dtype = CHOLMOD_DOUBLE;
    return d;
  }
};

CholeskyFactor::CholeskyFactor(const Eigen::SparseMatrix<double>& A_in)
    : impl_(std::make_shared<Impl>()) {
  Impl& m = *impl_;
  m.n = static_cast<int>(A_in.rows());
  if (A_in.rows() != A_in.cols()) {
    m.message = "matrix is not square";
    return;
  }
  Eigen::SparseMatrix<double> compressed;
  const Eigen::SparseMatrix<double>* A = &A_in;
  if (!A_in.isCompressed()) {
    compressed = A_in;
    compressed.makeCompressed();
    A = &compressed;
  }
  cholmod_sparse a = Impl::view(*A);

  Stopwatch clock;
  m.L = cholmod_analyze(&a, &m.common);
  m.analyse_seconds = clock.seconds();
  if (!m.L) {
    m.message = "CHOLMOD could not analyse the matrix (status " + std::to_string(m.common.status) + ")";
    return;
  }
  clock.restart();
  cholmod_factorize(&a, m.L, &m.common);
  m.factorize_seconds = clock.seconds();

  if (m.common.status == CHOLMOD_NOT_POSDEF || m.L->minor < m.L->n) {
    // L->minor is the first failed column of the permuted matrix; Perm maps it back to A.
    const int minor = static_cast<int>(m.L->minor);
    const int* perm = static_cast<const int*>(m.L->Perm);
    m.failed_column = (perm && minor < m.n) ? perm[minor] : minor;
    m.message = "not positive definite: the pivot of row " + std::to_string(m.failed_column) +
                " of " + std::to_string(m.n) + " is not positive";
    return;
  }
  if (m.common.status < CHOLMOD_OK) {
    m.message = "CHOLMOD failed to factorise (status " + std::to_string(m.common.status) + ")";
    return;
  }
  m.ok = true;
}

CholeskyFactor::CholeskyFactor(std::shared_ptr<Impl> impl, double scale)
    : impl_(std::move(impl)), scale_(scale) {}

CholeskyFactor::~CholeskyFactor() = default;

bool CholeskyFactor::ok() const { return impl_->ok; }
const std::string& CholeskyFactor::message() const { return impl_->message; }
int CholeskyFactor::size() const { return impl_->n; }
int CholeskyFactor::failed_column() const { return impl_->failed_column; }
double CholeskyFactor::analyse_seconds() const { return impl_->analyse_seconds; }
double CholeskyFactor::factorize_seconds() const { return impl_->factorize_seconds; }

long long CholeskyFactor::factor_nonzeros() const {
  const cholmod_factor* L = impl_->L;
  if (!L) return 0;
  if (L->is_super) {
    // Supernodal storage: each supernode is a dense block; count its lower trapezoid.
    long long total = 0;
    const int* super = static_cast<const int*>(L->super);
    const int* pi = static_cast<const int*>(L->pi);
    for (size_t s = 0; s < L->nsuper; ++s) {
      const long long cols = super[s + 1] - super[s];
      const long long rows = pi[s + 1] - pi[s];
      total += cols * rows - cols * (cols - 1) / 2;
    }
    return total;
  }
  const int* colcount = static_cast<const int*>(L->ColCount);
  long long total = 0;
  for (size_t j = 0; j < L->n; ++j) total += colcount[j];
  return total;
}

Eigen::MatrixXd CholeskyFactor::solve_columns(const Eigen::MatrixXd& b) const {
  Impl& m = *impl_;
  if (!m.ok || b.rows() != m.n) return Eigen::MatrixXd::Constant(b.rows(), b.cols(), 0.0);
  std::lock_guard<std::mutex> lock(m.mutex);
  cholmod_dense rhs = Impl::view(b);
  cholmod_dense* x = cholmod_solve(CHOLMOD_A, m.L, &rhs, &m.common);
  Eigen::MatrixXd result(b.rows(), b.cols());
  if (x) {
    result = Eigen::Map<const Eigen::MatrixXd>(static_cast<const double*>(x->x), b.rows(), b.cols());
    cholmod_free_dense(&x, &m.common);
  } else {
    result.setZero();
  }
  if (scale_ != 1.0) result /= scale_;
  return result;
}

Eigen::VectorXd CholeskyFactor::solve(const Eigen::VectorXd& b) const {
  const Eigen::MatrixXd x = solve_columns(Eigen::MatrixXd(b));
  return x.col(0);
}

std::shared_ptr<const CholeskyFactor> CholeskyFactor::scaled(double c) const {
  return std::shared_ptr<const CholeskyFactor>(new CholeskyFactor(impl_, scale_ * c));
}

}  // namespace contactqp
