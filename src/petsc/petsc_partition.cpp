// partition_graph() (contactqp/petsc/par_qp.hpp): PETSc's MatPartitioning, PT-Scotch by default
// (Debian's PETSc is built with it; ParMETIS is not in Debian's main archive).
#include <petscmat.h>

#include <algorithm>
#include <mutex>

#include "contactqp/petsc/par_qp.hpp"
#include "petsc_runtime.hpp"

namespace contactqp {
namespace {

struct PartitionFailure {
  std::string what;
  PetscErrorCode code;
};

void check_partition(PetscErrorCode code, const char* what) {
  if (code) throw PartitionFailure{what, code};
}

}  // namespace

std::vector<int> partition_graph(const std::vector<long>& offsets, const std::vector<int>& neighbours, int parts,
                                 const std::string& petsc_options) {
  const int n = static_cast<int>(offsets.size()) - 1;
  std::vector<int> part(std::max(n, 0), 0);
  if (parts <= 1 || n <= 0) return part;
  std::lock_guard<std::mutex> lock(detail::petsc_mutex());
  detail::PetscRuntime::instance(petsc_options);
  Mat adjacency = nullptr;
  MatPartitioning partitioning = nullptr;
  IS mine = nullptr, all = nullptr;
  try {
    // This rank's block of vertices, each with its neighbours but itself (MATMPIADJ takes the
    // arrays, allocated by PETSc).
    PetscInt local = PETSC_DECIDE, global = n, end = 0;
    check_partition(PetscSplitOwnership(PETSC_COMM_WORLD, &local, &global), "PetscSplitOwnership");
    MPI_Scan(&local, &end, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD);
    const PetscInt first = end - local;
    PetscInt *ia = nullptr, *ja = nullptr;
    long edges = 0;
    for (PetscInt v = first; v < end; ++v)
      for (long k = offsets[v]; k < offsets[v + 1]; ++k) edges += neighbours[k] != v;
    check_partition(PetscMalloc1(local + 1, &ia), "PetscMalloc1");
    check_partition(PetscMalloc1(std::max(edges, 1L), &ja), "PetscMalloc1");
    ia[0] = 0;
    for (PetscInt v = first; v < end; ++v) {
      PetscInt count = ia[v - first];
      for (long k = offsets[v]; k < offsets[v + 1]; ++k)
        if (neighbours[k] != v) ja[count++] = neighbours[k];
      ia[v - first + 1] = count;
    }
    check_partition(MatCreateMPIAdj(PETSC_COMM_WORLD, local, n, ia, ja, nullptr, &adjacency), "MatCreateMPIAdj");
    check_partition(MatPartitioningCreate(PETSC_COMM_WORLD, &partitioning), "MatPartitioningCreate");
    check_partition(MatPartitioningSetAdjacency(partitioning, adjacency), "MatPartitioningSetAdjacency");
    check_partition(MatPartitioningSetNParts(partitioning, parts), "MatPartitioningSetNParts");
    check_partition(MatPartitioningSetType(partitioning, MATPARTITIONINGPTSCOTCH), "MatPartitioningSetType");
    check_partition(MatPartitioningSetFromOptions(partitioning), "MatPartitioningSetFromOptions");
    check_partition(MatPartitioningApply(partitioning, &mine), "MatPartitioningApply");
    check_partition(ISAllGather(mine, &all), "ISAllGather");
    const PetscInt* indices = nullptr;
    check_partition(ISGetIndices(all, &indices), "ISGetIndices");
    for (int v = 0; v < n; ++v) part[v] = static_cast<int>(indices[v]);
    ISRestoreIndices(all, &indices);
  } catch (const PartitionFailure&) {
    part.clear();
  }
  // Every rank must own elements by the same rows: without a partition anywhere, none at all
  // (the caller goes on in the DOFs' own order, and says so).
  int failed = part.empty(), any_failed = 0;
  MPI_Allreduce(&failed, &any_failed, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  if (any_failed) part.clear();
  if (all) ISDestroy(&all);
  if (mine) ISDestroy(&mine);
  if (partitioning) MatPartitioningDestroy(&partitioning);
  if (adjacency) MatDestroy(&adjacency);
  return part;
}

}  // namespace contactqp
