// CHOLMOD behind the CholeskyFactor interface. Only this file includes <cholmod.h>.
#include "contactqp/cholesky.hpp"

#include <cholmod.h>

#include <algorithm>
#include <mutex>
#include <vector>

#include "contactqp/errors.hpp"
#include "contactqp/timer.hpp"

// The BLAS that CHOLMOD's supernodal kernels use (OpenBLAS on Debian), for the dense blocks
// of condense(): column-major, Fortran calling convention.
extern "C" {
void dtrsm_(const char* side, const char* uplo, const char* trans, const char* diag, const int* m, const int* n,
            const double* alpha, const double* A, const int* lda, double* B, const int* ldb);
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k, const double* alpha,
            const double* A, const int* lda, const double* B, const int* ldb, const double* beta, double* C,
            const int* ldc);
void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha, const double* A,
            const int* lda, const double* beta, double* C, const int* ldc);
}

namespace contactqp {

struct CholeskyFactor::Impl {
  cholmod_common common;
  cholmod_factor* L = nullptr;
  int n = 0;
  bool ok = false;
  int failed_column = -1;
  std::string message;
  double analyse_seconds = 0, factorize_seconds = 0;
  long long solves = 0;  // right-hand sides solved, under `mutex`
  std::mutex mutex;      // CHOLMOD's workspace lives in `common`: one solve at a time

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

namespace {

// The fill-reducing ordering CHOLMOD's analysis tries.
void set_ordering(cholmod_common& common, Ordering ordering) {
  switch (ordering) {
    case Ordering::Auto:
      break;  // nmethods = 0: AMD, then METIS too when AMD's fill is high
    case Ordering::Amd:
      common.nmethods = 1;
      common.method[0].ordering = CHOLMOD_AMD;
      break;
    case Ordering::Metis:
      common.nmethods = 1;
      common.method[0].ordering = CHOLMOD_METIS;
      break;
  }
}

// nnz(L) of a symbolic or numeric factor, whose integers are Int (int, or SuiteSparse_long for
// CHOLMOD's cholmod_l_ interface).
template <typename Int = int>
long long count_nonzeros(const cholmod_factor* L) {
  if (!L) return 0;
  if (L->is_super) {
    // Supernodal storage: each supernode is a dense block; count its lower trapezoid.
    long long total = 0;
    const Int* super = static_cast<const Int*>(L->super);
    const Int* pi = static_cast<const Int*>(L->pi);
    for (size_t s = 0; s < L->nsuper; ++s) {
      const long long cols = super[s + 1] - super[s];
      const long long rows = pi[s + 1] - pi[s];
      total += cols * rows - cols * (cols - 1) / 2;
    }
    return total;
  }
  const Int* colcount = static_cast<const Int*>(L->ColCount);
  long long total = 0;
  for (size_t j = 0; j < L->n; ++j) total += colcount[j];
  return total;
}

// A in compressed storage, as CHOLMOD reads it: A itself, or a compressed copy kept in `storage`.
const Eigen::SparseMatrix<double>& compressed(const Eigen::SparseMatrix<double>& A,
                                              Eigen::SparseMatrix<double>& storage) {
  if (A.isCompressed()) return A;
  storage = A;
  storage.makeCompressed();
  return storage;
}

// CHOLMOD's status in words, with what to do about the two a large problem meets.
std::string status_text(int status) {
  switch (status) {
    case CHOLMOD_OUT_OF_MEMORY:
      return "out of memory (status -2): the factor does not fit; --linear-solver petsc needs no factor";
    case CHOLMOD_TOO_LARGE:
      return "the factor would exceed 2^31 entries, the limit of 32-bit indices (status -3); "
             "--linear-solver petsc needs no factor";
    default:
      return "status " + std::to_string(status);
  }
}

std::string ordering_label(const cholmod_factor* L) {
  if (!L) return "none";
  switch (L->ordering) {
    case CHOLMOD_NATURAL:
      return "natural";
    case CHOLMOD_GIVEN:
      return "given";
    case CHOLMOD_AMD:
      return "amd";
    case CHOLMOD_METIS:
      return "metis";
    case CHOLMOD_NESDIS:
      return "nesdis";
    case CHOLMOD_COLAMD:
      return "colamd";
    case CHOLMOD_POSTORDERED:
      return "postordered";
  }
  return "unknown";
}

}  // namespace

CholeskyFactor::CholeskyFactor(const Eigen::SparseMatrix<double>& A_in, Ordering ordering)
    : impl_(std::make_shared<Impl>()) {
  Impl& m = *impl_;
  set_ordering(m.common, ordering);
  m.n = static_cast<int>(A_in.rows());
  if (A_in.rows() != A_in.cols()) {
    m.message = "matrix is not square";
    return;
  }
  Eigen::SparseMatrix<double> storage;
  const Eigen::SparseMatrix<double>* A = &compressed(A_in, storage);
  cholmod_sparse a = Impl::view(*A);

  Stopwatch clock;
  m.L = cholmod_analyze(&a, &m.common);
  m.analyse_seconds = clock.seconds();
  if (!m.L) {
    m.message = "CHOLMOD could not analyse the matrix: " + status_text(m.common.status);
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
    m.message = "not positive definite: the pivot of row " + std::to_string(m.failed_column) + " of " +
                std::to_string(m.n) + " is not positive";
    return;
  }
  if (m.common.status < CHOLMOD_OK) {
    m.message = "CHOLMOD failed to factorise: " + status_text(m.common.status);
    return;
  }
  m.ok = true;
}

CholeskyFactor::CholeskyFactor(std::shared_ptr<Impl> impl, double scale) : impl_(std::move(impl)), scale_(scale) {}

CholeskyFactor::~CholeskyFactor() = default;

bool CholeskyFactor::ok() const { return impl_->ok; }
const std::string& CholeskyFactor::message() const { return impl_->message; }
int CholeskyFactor::size() const { return impl_->n; }
int CholeskyFactor::failed_column() const { return impl_->failed_column; }
double CholeskyFactor::analyse_seconds() const { return impl_->analyse_seconds; }
double CholeskyFactor::factorize_seconds() const { return impl_->factorize_seconds; }

long long CholeskyFactor::factor_nonzeros() const { return count_nonzeros(impl_->L); }

bool CholeskyFactor::supernodal() const { return impl_->L && impl_->L->is_super; }

std::string CholeskyFactor::ordering_name() const { return ordering_label(impl_->L); }

FactorPrediction CholeskyFactor::predict(const Eigen::SparseMatrix<double>& A_in, Ordering ordering) {
  FactorPrediction p;
  if (A_in.rows() != A_in.cols()) {
    p.message = "matrix is not square";
    return p;
  }
  Eigen::SparseMatrix<double> storage;
  const Eigen::SparseMatrix<double>* A = &compressed(A_in, storage);
  // The analysis runs on CHOLMOD's 64-bit-index interface (cholmod_l_*), on the pattern alone:
  // the factor the 32-bit interface builds (the one CholeskyFactor uses) is limited to 2^31
  // entries, and the prediction must say by how much a large problem exceeds that.
  const long n = A->rows();
  std::vector<SuiteSparse_long> column_start(A->outerIndexPtr(), A->outerIndexPtr() + n + 1);
  std::vector<SuiteSparse_long> row_index(A->innerIndexPtr(), A->innerIndexPtr() + A->nonZeros());
  cholmod_sparse a{};
  a.nrow = a.ncol = n;
  a.nzmax = A->nonZeros();
  a.p = column_start.data();
  a.i = row_index.data();
  a.stype = -1;
  a.itype = CHOLMOD_LONG;
  a.xtype = CHOLMOD_PATTERN;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;
  a.packed = 1;
  cholmod_common common;
  cholmod_l_start(&common);
  common.print = 0;
  set_ordering(common, ordering);
  Stopwatch clock;
  cholmod_factor* L = cholmod_l_analyze(&a, &common);
  p.analyse_seconds = clock.seconds();
  if (!L) {
    p.message = "CHOLMOD could not analyse the matrix: " + status_text(common.status);
    cholmod_l_finish(&common);
    return p;
  }
  p.ok = true;
  p.ordering = ordering_label(L);
  p.supernodal = L->is_super;
  p.factor_nonzeros = count_nonzeros<SuiteSparse_long>(L);
  // What factorising would allocate for L: its values (a supernodal factor stores each
  // supernode's dense block, xsize entries) and its integer pattern (32-bit indices).
  const double values = L->is_super ? static_cast<double>(L->xsize) : static_cast<double>(p.factor_nonzeros);
  const double indices = L->is_super ? static_cast<double>(L->ssize) : static_cast<double>(p.factor_nonzeros);
  p.factor_bytes = 8.0 * values + 4.0 * indices;
  p.fits_32bit_indices = std::max(values, indices) < 2147483647.0;
  p.flops = common.fl;
  cholmod_l_free_factor(&L, &common);
  cholmod_l_finish(&common);
  return p;
}

LinearSolverStatistics CholeskyFactor::statistics() const {
  LinearSolverStatistics s;
  s.name = "cholmod";
  s.method = std::string(supernodal() ? "supernodal" : "simplicial") + " LLᵀ, " + ordering_name() + " ordering";
  s.setup_seconds = impl_->analyse_seconds + impl_->factorize_seconds;
  s.factor_nonzeros = factor_nonzeros();
  std::lock_guard<std::mutex> lock(impl_->mutex);
  s.solves = impl_->solves;
  return s;
}

Eigen::MatrixXd CholeskyFactor::solve_columns(const Eigen::MatrixXd& b) const {
  Impl& m = *impl_;
  if (!m.ok || b.rows() != m.n) return Eigen::MatrixXd::Constant(b.rows(), b.cols(), 0.0);
  std::lock_guard<std::mutex> lock(m.mutex);
  cholmod_dense rhs = Impl::view(b);
  cholmod_dense* x = cholmod_solve(CHOLMOD_A, m.L, &rhs, &m.common);
  m.solves += b.cols();
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

namespace {

// One column block of L: a supernode, or one column of a simplicial factor. Its values are a
// dense column-major nrows × ncols array (leading dimension nrows) whose first ncols rows are
// the block's own columns (a lower triangle) and the rest the rows below them, all of them
// ancestors of the block in the elimination tree.
struct Block {
  int first_column = 0, ncols = 0, nrows = 0;
  const int* rows = nullptr;  // nrows row indices of L (permuted numbering)
  const double* values = nullptr;
};

// The blocks of a numeric LLᵀ factor, supernodal or simplicial, in elimination order: a
// block's ancestors come after it.
class BlockView {
 public:
  explicit BlockView(const cholmod_factor& L) : L_(L) {
    if (L.is_super) {
      const int* super = static_cast<const int*>(L.super);
      block_of_.resize(L.n);
      for (size_t s = 0; s < L.nsuper; ++s)
        for (int j = super[s]; j < super[s + 1]; ++j) block_of_[j] = static_cast<int>(s);
    }
  }
  int count() const { return static_cast<int>(L_.is_super ? L_.nsuper : L_.n); }
  int block_of(int column) const { return L_.is_super ? block_of_[column] : column; }
  Block block(int b) const {
    Block block;
    if (L_.is_super) {
      const int* super = static_cast<const int*>(L_.super);
      const int* pi = static_cast<const int*>(L_.pi);
      const int* px = static_cast<const int*>(L_.px);
      block.first_column = super[b];
      block.ncols = super[b + 1] - super[b];
      block.nrows = pi[b + 1] - pi[b];
      block.rows = static_cast<const int*>(L_.s) + pi[b];
      block.values = static_cast<const double*>(L_.x) + px[b];
    } else {
      // Simplicial LLᵀ: the diagonal entry comes first in each column.
      const int* p = static_cast<const int*>(L_.p);
      block.first_column = b;
      block.ncols = 1;
      block.nrows = static_cast<const int*>(L_.nz)[b];
      block.rows = static_cast<const int*>(L_.i) + p[b];
      block.values = static_cast<const double*>(L_.x) + p[b];
    }
    return block;
  }

 private:
  const cholmod_factor& L_;
  std::vector<int> block_of_;
};

// `into` ∪= `from`, both sorted without repetitions.
void merge_into(std::vector<int>& into, const std::vector<int>& from) {
  if (std::includes(into.begin(), into.end(), from.begin(), from.end())) return;
  std::vector<int> merged;
  merged.reserve(into.size() + from.size());
  std::set_union(into.begin(), into.end(), from.begin(), from.end(), std::back_inserter(merged));
  into.swap(merged);
}

// Position in `superset` of each entry of `subset` (both sorted; subset ⊆ superset).
void positions_in(const std::vector<int>& subset, const std::vector<int>& superset, std::vector<int>& positions) {
  positions.resize(subset.size());
  size_t k = 0;
  for (size_t a = 0; a < subset.size(); ++a) {
    while (superset[k] != subset[a]) ++k;
    positions[a] = static_cast<int>(k);
  }
}

}  // namespace

Condensation CholeskyFactor::condense(const Eigen::SparseMatrix<double>& C, const Eigen::VectorXd& b) const {
  using Eigen::MatrixXd;
  Impl& impl = *impl_;
  const int m = static_cast<int>(C.rows());
  Condensation out;
  out.S = MatrixXd::Zero(m, m);
  out.c = Eigen::VectorXd::Zero(m);
  if (!impl.ok || C.cols() != impl.n || b.size() != impl.n) return out;
  std::lock_guard<std::mutex> lock(impl.mutex);
  cholmod_factor& L = *impl.L;

  // y = L⁻¹ P b: the forward half of one solve.
  Eigen::VectorXd y = Eigen::VectorXd::Zero(impl.n);
  {
    const Eigen::MatrixXd rhs = b;
    cholmod_dense in = Impl::view(rhs);
    cholmod_dense* permuted = cholmod_solve(CHOLMOD_P, &L, &in, &impl.common);
    cholmod_dense* forward = permuted ? cholmod_solve(CHOLMOD_L, &L, permuted, &impl.common) : nullptr;
    if (forward) y = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(forward->x), impl.n);
    cholmod_free_dense(&permuted, &impl.common);
    cholmod_free_dense(&forward, &impl.common);
  }

  const BlockView blocks(L);
  const int n_blocks = blocks.count();
  std::vector<int> inverse_perm(impl.n);
  const int* perm = static_cast<const int*>(L.Perm);
  for (int k = 0; k < impl.n; ++k) inverse_perm[perm ? perm[k] : k] = k;
  const Eigen::SparseMatrix<double> Ct = C.transpose();  // column j: row j of C

  // Symbolic pass: live[s] lists the columns j of W that are nonzero in block s. Column j
  // starts at the blocks of C's row j and spreads to every block its rows below reach.
  std::vector<std::vector<int>> live(n_blocks);
  for (int j = 0; j < m; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(Ct, j); it; ++it) {
      std::vector<int>& list = live[blocks.block_of(inverse_perm[it.row()])];
      if (list.empty() || list.back() != j) list.push_back(j);
    }
  for (int s = 0; s < n_blocks; ++s) {
    if (live[s].empty()) continue;
    const Block block = blocks.block(s);
    int previous = -1;
    for (int q = block.ncols; q < block.nrows; ++q) {
      const int t = blocks.block_of(block.rows[q]);
      if (t != previous) merge_into(live[t], live[s]);
      previous = t;
    }
  }

  // Numeric pass, block by block in elimination order: W_s = L_ss⁻¹ (rhs_s − updates from
  // below), then S += W_sᵀW_s and c += W_sᵀ y_s, then push L_os W_s up to the ancestors.
  std::vector<MatrixXd> W(n_blocks);
  long long held = 0;
  auto allocate = [&](int s) {
    if (W[s].size() == 0) {
      W[s] = MatrixXd::Zero(blocks.block(s).ncols, static_cast<Eigen::Index>(live[s].size()));
      held += W[s].size();
      out.peak_entries = std::max(out.peak_entries, held);
    }
  };
  for (int j = 0; j < m; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(Ct, j); it; ++it) {
      const int k = inverse_perm[it.row()];
      const int s = blocks.block_of(k);
      allocate(s);
      const auto position = std::lower_bound(live[s].begin(), live[s].end(), j) - live[s].begin();
      W[s](k - blocks.block(s).first_column, position) += it.value();
    }

  std::vector<int> positions;
  MatrixXd gram, update;
  const double one = 1, zero = 0;
  for (int s = 0; s < n_blocks; ++s) {
    const std::vector<int>& columns = live[s];
    if (columns.empty()) continue;
    allocate(s);
    const Block block = blocks.block(s);
    const int k = static_cast<int>(columns.size());
    MatrixXd& Ws = W[s];
    // W_s = L_ss⁻¹ W_s, then S += W_sᵀW_s and c += W_sᵀ y_s. A simplicial factor has blocks of
    // one column, too small to be worth a BLAS call each.
    if (block.ncols == 1)
      Ws /= block.values[0];
    else
      dtrsm_("L", "L", "N", "N", &block.ncols, &k, &one, block.values, &block.nrows, Ws.data(), &block.ncols);
    out.reached_columns += block.ncols;
    out.entries += Ws.size();
    const Eigen::VectorXd cy = Ws.transpose() * y.segment(block.first_column, block.ncols);
    for (int a = 0; a < k; ++a) out.c[columns[a]] += cy[a];
    if (block.ncols == 1) {
      for (int c = 0; c < k; ++c)
        for (int a = c; a < k; ++a) out.S(columns[a], columns[c]) += Ws(0, a) * Ws(0, c);
    } else if (columns.back() - columns.front() + 1 == k) {
      // Consecutive columns (near the root, all of them): accumulate in place.
      dsyrk_("L", "T", &k, &block.ncols, &one, Ws.data(), &block.ncols, &one, &out.S(columns.front(), columns.front()),
             &m);
    } else {
      gram.resize(k, k);
      dsyrk_("L", "T", &k, &block.ncols, &one, Ws.data(), &block.ncols, &zero, gram.data(), &k);
      for (int c = 0; c < k; ++c)
        for (int a = c; a < k; ++a) out.S(columns[a], columns[c]) += gram(a, c);  // lower: columns sorted
    }

    const int below = block.nrows - block.ncols;
    if (below > 0) {
      update.resize(below, k);
      if (block.ncols == 1)
        update = Eigen::Map<const Eigen::VectorXd>(block.values + 1, below) * Ws;
      else
        dgemm_("N", "N", &below, &k, &block.ncols, &one, block.values + block.ncols, &block.nrows, Ws.data(),
               &block.ncols, &zero, update.data(), &below);
      // Rows below come sorted in a supernode, so they fall into runs with one ancestor each.
      for (int q = 0; q < below;) {
        const int t = blocks.block_of(block.rows[block.ncols + q]);
        int end = q + 1;
        while (end < below && blocks.block_of(block.rows[block.ncols + end]) == t) ++end;
        allocate(t);
        positions_in(columns, live[t], positions);
        const int first = blocks.block(t).first_column;
        for (int a = 0; a < k; ++a) {
          double* target = W[t].col(positions[a]).data();
          const double* source = update.col(a).data();
          for (int r = q; r < end; ++r) target[block.rows[block.ncols + r] - first] -= source[r];
        }
        q = end;
      }
    }
    held -= Ws.size();
    Ws.resize(0, 0);  // its contributions are passed on: W itself is not kept
  }
  out.S.triangularView<Eigen::StrictlyUpper>() = out.S.transpose();
  if (scale_ != 1.0) {
    // The factor stands for scale·A: S and c scale with its inverse.
    out.S /= scale_;
    out.c /= scale_;
  }
  return out;
}

std::shared_ptr<const CholeskyFactor> CholeskyFactor::scaled(double c) const {
  return std::shared_ptr<const CholeskyFactor>(new CholeskyFactor(impl_, scale_ * c));
}

}  // namespace contactqp
