// The PETSc solver of K, seen from the rest of cqp_qp: no PETSc header here. Built from
// petsc_solver.cpp when CONTACTQP_WITH_PETSC is on, else from petsc_unavailable.cpp.
#pragma once

#include <memory>

#include "contactqp/linear_solver.hpp"

namespace contactqp::detail {

bool petsc_available();
void start_petsc_runtime(const std::string& options);

// A KSP on a PETSc copy of A (docs/linear-solvers.md). Throws InputError when the PETSc
// options are bad input that PETSc reports before any work; numerical failures go to ok().
std::shared_ptr<const LinearSolver> make_petsc_solver(const Eigen::SparseMatrix<double>& A,
                                                      const LinearSolverOptions& options);

}  // namespace contactqp::detail

namespace contactqp::detail {

// MPI as PETSc started it: -1 (rank) and 0 (size) while MPI does not run or is finalised.
int mpi_rank();
int mpi_size();
void mpi_sum(double* values, long n);  // MPI_Allreduce in place on MPI_COMM_WORLD
// agree_on_exit() (processes.hpp) on MPI_COMM_WORLD.
int mpi_agree_on_exit(int status, const std::string& error_line, double timeout_seconds);

}  // namespace contactqp::detail
