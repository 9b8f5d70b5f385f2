// Built instead of petsc_solver.cpp when PETSc is absent: the petsc linear solver reports
// itself unavailable, and make_linear_solver() refuses it as bad input before any work.
#include "contactqp/errors.hpp"
#include "contactqp/processes.hpp"
#include "petsc_bound_qp.hpp"
#include "petsc_solver.hpp"

namespace contactqp::detail {

bool petsc_available() { return false; }

void start_petsc_runtime(const std::string&) {}  // Ipopt's sequential MUMPS is the only one

std::shared_ptr<const LinearSolver> make_petsc_solver(const Eigen::SparseMatrix<double>&, const LinearSolverOptions&) {
  throw InputError("linear_solver", "= \"petsc\": PETSc was not built into this copy of contactqp");
}

}  // namespace contactqp::detail

namespace contactqp::detail {

int mpi_rank() { return -1; }
int mpi_size() { return 0; }
void mpi_sum(double*, long) {}                                                    // never called: size 0
int mpi_agree_on_exit(int status, const std::string&, double) { return status; }  // never called: size 0

bool petsc_bound_qp_available() { return false; }
BoundQpResult solve_bound_qp_petsc(BoundQp, const BoundQpOptions&) {
  throw InputError("backend", "= \"petsc\": PETSc was not built into this copy of contactqp");
}

}  // namespace contactqp::detail

namespace contactqp {

std::vector<int> partition_graph(const std::vector<long>& offsets, const std::vector<int>&, int, const std::string&) {
  return std::vector<int>(offsets.empty() ? 0 : offsets.size() - 1, 0);  // one process: one part
}

}  // namespace contactqp
