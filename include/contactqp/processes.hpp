// Several processes under mpirun (the petsc backend, docs/petsc.md): which one this is, and how
// they end together. Without MPI every function describes a single process.
#pragma once

#include <string>
#include <vector>

namespace contactqp {

// This process's MPI rank once MPI runs; before that the launcher's (OMPI_COMM_WORLD_RANK,
// PMIX_RANK or PMI_RANK in the environment), else 0. Only rank 0 prints and writes files.
int process_rank();
// The number of MPI processes once MPI runs (the launcher's count before), else 1.
int process_count();

// In place, the sum of `values` over the ranks (MPI_Allreduce; collective). Nothing while MPI
// does not run on several processes. For QPs whose K each rank holds a share of (qp.hpp).
void sum_over_ranks(double* values, long n);

// Splits a graph (vertex v's neighbours are neighbours[offsets[v]] .. neighbours[offsets[v + 1] − 1])
// into `parts` parts of nearly equal size with few edges between them: PETSc's
// MatPartitioning with PT-Scotch (-mat_partitioning_type in `petsc_options` or PETSC_OPTIONS
// chooses another). part[v] for every vertex, the same on every rank. Collective under
// mpirun; starts PETSc. All zeros for one part or without PETSc; empty if PETSc failed.
std::vector<int> partition_graph(const std::vector<long>& offsets, const std::vector<int>& neighbours, int parts,
                                 const std::string& petsc_options = "");

// How a run ends on every rank at once. Every rank passes its exit status and its error line
// (empty when it has none); the lowest rank with a line prints it to stderr, once for the run,
// and the result is the largest status. Collective while MPI runs on several processes. A
// rank that failed waits at most `timeout_seconds` for the others (they may be stuck in a
// collective call it left), then prints its line and ends them all (MPI_Abort): never a hang.
int agree_on_exit(int status, const std::string& error_line, double timeout_seconds = 60);

}  // namespace contactqp
