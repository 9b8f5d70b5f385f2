// The parts of the LinearSolver interface that do not depend on a library: the generic
// multi-column solve and condensation, and the factory with the solvers libraries register
// (the name tables: linear_solver_names.cpp).
#include "contactqp/linear_solver.hpp"

#include <algorithm>
#include <mutex>
#include <utility>

#include "contactqp/cholesky.hpp"
#include "contactqp/errors.hpp"
#include "qp/builtins.hpp"

namespace contactqp {
namespace {

// Right-hand sides per solve_columns() call of the generic condensation: enough to amortise a
// call, few enough that the dense block (n × kCondenseBlock) stays small next to K.
constexpr int kCondenseBlock = 32;

// The factories libraries registered, by kind (CHOLMOD's is built in).
struct Factories {
  std::mutex mutex;
  std::map<LinearSolverKind, LinearSolverFactory> by_kind;
};

Factories& factories() {
  static Factories registered;
  return registered;
}

LinearSolverFactory registered_factory(LinearSolverKind kind) {
  detail::register_builtins();
  Factories& all = factories();
  std::lock_guard<std::mutex> lock(all.mutex);
  const auto found = all.by_kind.find(kind);
  return found == all.by_kind.end() ? LinearSolverFactory() : found->second;
}

}  // namespace

void register_linear_solver(LinearSolverKind kind, LinearSolverFactory factory) {
  Factories& all = factories();
  std::lock_guard<std::mutex> lock(all.mutex);
  all.by_kind[kind] = std::move(factory);
}

bool linear_solver_available(LinearSolverKind kind) {
  return kind == LinearSolverKind::Cholmod || static_cast<bool>(registered_factory(kind));
}

Eigen::VectorXd LinearSolver::solve(const Eigen::VectorXd& b, const Eigen::VectorXd&) const { return solve(b); }

Eigen::MatrixXd LinearSolver::solve_columns(const Eigen::MatrixXd& b) const {
  Eigen::MatrixXd x(b.rows(), b.cols());
  for (Eigen::Index j = 0; j < b.cols(); ++j) x.col(j) = solve(Eigen::VectorXd(b.col(j)));
  return x;
}

Condensation LinearSolver::condense(const Eigen::SparseMatrix<double>& C, const Eigen::VectorXd& b) const {
  const int m = static_cast<int>(C.rows());
  Condensation out;
  out.S = Eigen::MatrixXd::Zero(m, m);
  out.c = Eigen::VectorXd::Zero(m);
  if (!ok() || C.cols() != size() || b.size() != size()) return out;
  out.c = C * solve(b);
  const Eigen::SparseMatrix<double> Ct = C.transpose();
  for (int first = 0; first < m; first += kCondenseBlock) {
    const int k = std::min(kCondenseBlock, m - first);
    const Eigen::MatrixXd X = solve_columns(Eigen::MatrixXd(Ct.middleCols(first, k)));
    out.S.middleCols(first, k) = C * X;
  }
  // An iterative solver's columns carry their own small errors: S is symmetric only to that
  // accuracy, and the LCP's Cholesky of its blocks wants it exactly symmetric.
  const Eigen::MatrixXd S = out.S;
  out.S = 0.5 * (S + S.transpose());
  return out;
}

std::shared_ptr<const LinearSolver> make_linear_solver(const Eigen::SparseMatrix<double>& A,
                                                       const LinearSolverOptions& options) {
  if (options.kind == LinearSolverKind::Cholmod) return std::make_shared<const CholeskyFactor>(A, options.ordering);
  const LinearSolverFactory factory = registered_factory(options.kind);
  if (!factory)
    throw InputError("linear_solver", "= " + to_string(options.kind) +
                                          ": was not built into this copy of contactqp (its library was absent at "
                                          "configure time; docs/install.md)");
  return factory(A, options);
}

}  // namespace contactqp
