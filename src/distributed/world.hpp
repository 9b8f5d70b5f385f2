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

}  // namespace contactqp::detail
