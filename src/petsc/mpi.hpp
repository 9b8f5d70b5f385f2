// MPI as the room uses it, seen without MPI's headers: defined in petsc_runtime.cpp (MPI as
// PETSc started it), or without PETSc in without_petsc.cpp (one process).
#pragma once

#include <map>
#include <string>

#include "contactqp/processes.hpp"

namespace contactqp::detail {

// -1 (rank) and 0 (size) while MPI does not run or is finalised.
int mpi_rank();
int mpi_size();
// In place, the sum over the ranks (MPI_Allreduce on MPI_COMM_WORLD; collective). Nothing on one rank.
void sum_over_ranks(double* values, long n);
// connect_processes() (processes.hpp): MPI alone, before PETSc.
void connect_mpi();
// agree_on_failure() (processes.hpp), on a communicator of its own.
AgreedFailure mpi_agree_on_failure(int status, const std::string& error, double timeout_seconds);
// Starts PETSc (and MPI, when nobody did) with the user's PETSc options on its command line.
void start_petsc_runtime(const std::map<std::string, std::string>& library_options);

// PETSc's options database entries in SolveOptions::library_options ("petsc"), or "".
std::string petsc_options_of(const std::map<std::string, std::string>& library_options);

}  // namespace contactqp::detail
