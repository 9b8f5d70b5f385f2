// Built instead of petsc_solver.cpp when PETSc is absent: the petsc linear solver reports
// itself unavailable, and make_linear_solver() refuses it as bad input before any work.
#include "contactqp/errors.hpp"
#include "petsc_solver.hpp"

namespace contactqp::detail {

bool petsc_available() { return false; }

void start_petsc_runtime(const std::string&) {}  // Ipopt's sequential MUMPS is the only one

std::shared_ptr<const LinearSolver> make_petsc_solver(const Eigen::SparseMatrix<double>&, const LinearSolverOptions&) {
  throw InputError("linear_solver", "= \"petsc\": PETSc was not built into this copy of contactqp");
}

}  // namespace contactqp::detail
