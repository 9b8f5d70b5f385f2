// The parts of the LinearSolver interface that do not depend on a library: the generic
// multi-column solve and condensation, and the factory (the name tables: linear_solver_names.cpp).
#include "contactqp/linear_solver.hpp"

#include <algorithm>
#include <utility>

#include "contactqp/cholesky.hpp"
#include "contactqp/errors.hpp"
#include "petsc_solver.hpp"

namespace contactqp {
namespace {

// Right-hand sides per solve_columns() call of the generic condensation: enough to amortise a
// call, few enough that the dense block (n × kCondenseBlock) stays small next to K.
constexpr int kCondenseBlock = 32;

}  // namespace

bool linear_solver_available(LinearSolverKind kind) {
  switch (kind) {
    case LinearSolverKind::Cholmod:
      return true;
    case LinearSolverKind::Petsc:
      return detail::petsc_available();
  }
  return false;
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

void start_petsc_runtime(const std::string& petsc_options) { detail::start_petsc_runtime(petsc_options); }

std::shared_ptr<const LinearSolver> make_linear_solver(const Eigen::SparseMatrix<double>& A,
                                                       const LinearSolverOptions& options) {
  switch (options.kind) {
    case LinearSolverKind::Cholmod:
      require(!options.rank_share, "linear_solver", to_string(options.kind),
              "cannot factorise a matrix assembled in shares over the MPI ranks (use petsc)");
      return std::make_shared<const CholeskyFactor>(A, options.ordering);
    case LinearSolverKind::Petsc:
      require(detail::petsc_available(), "linear_solver", to_string(options.kind),
              "PETSc was not built into this copy of contactqp (install petsc-dev and reconfigure with "
              "-DCONTACTQP_WITH_PETSC=ON)");
      return detail::make_petsc_solver(A, options);
  }
  throw InputError("linear_solver", "= " + std::to_string(static_cast<int>(options.kind)) + ": not a linear solver");
}

}  // namespace contactqp
