// Built instead of the files that include PETSc when PETSc is absent: one process, no PETSc
// solver of K (nothing registers LinearSolverKind::Petsc), and the petsc backend registered as
// unavailable (petsc_backend.cpp), so that solve() refuses it before any of these is reached.
#include "contactqp/errors.hpp"
#include "contactqp/petsc/par_qp.hpp"
#include "mpi.hpp"
#include "petsc_bound_qp.hpp"
#include "petsc_solver.hpp"

namespace contactqp::detail {
namespace {

[[noreturn]] void not_built() {
  throw InputError("backend", "= \"petsc\": PETSc was not built into this copy of contactqp");
}

}  // namespace

int mpi_rank() { return -1; }
int mpi_size() { return 0; }
void sum_over_ranks(double*, long) {}
void connect_mpi() {}
AgreedFailure mpi_agree_on_failure(int status, const std::string& error, double) {
  return {status, error, error.empty() ? -1 : 0, !error.empty()};
}

std::shared_ptr<const LinearSolver> make_petsc_solver(const Eigen::SparseMatrix<double>&, const LinearSolverOptions&,
                                                      const MatrixLayout&) {
  not_built();
}

BoundQpResult solve_bound_qp_petsc(BoundQp, const BoundQpOptions&, BoundQpChain*) { not_built(); }

}  // namespace contactqp::detail

namespace contactqp {

std::vector<int> partition_graph(const std::vector<long>& offsets, const std::vector<int>&, int, const std::string&) {
  return std::vector<int>(offsets.empty() ? 0 : offsets.size() - 1, 0);  // one process: one part
}

}  // namespace contactqp
