// This process's place among the MPI processes of a distributed run (MPI_COMM_WORLD, which
// PETSc's PETSC_COMM_WORLD is here).
#pragma once

#include <mpi.h>

namespace contactqp::detail {

inline int world_rank() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

inline int world_size() {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

// This rank's first number when every rank numbers its n things consecutively after the
// lower ranks'; `total` receives the count over all ranks. Collective.
inline long long first_of_mine(long long n, long long* total) {
  long long first = 0;
  MPI_Exscan(&n, &first, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  if (world_rank() == 0) first = 0;  // MPI_Exscan leaves rank 0's result undefined
  MPI_Allreduce(&n, total, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  return first;
}

}  // namespace contactqp::detail
