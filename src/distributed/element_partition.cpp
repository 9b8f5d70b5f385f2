// partition_elements() (element_partition.hpp).
#include "element_partition.hpp"

#include <petscmat.h>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

#include "coarse_lattice.hpp"
#include "petsc/petsc_runtime.hpp"

namespace contactqp::detail {
namespace {

void check_coarse_partition(PetscErrorCode code, const char* what) {
  if (code) throw std::runtime_error(std::string("partitioning the coarse mesh: ") + what + ": " + error_text(code));
}

// The elements that share a face with each element (CSR, without itself): each face's
// vertices sorted, the list of (face, element) sorted, equal neighbours joined.
void dual_graph(const Mesh& mesh, std::vector<PetscInt>& offsets, std::vector<PetscInt>& neighbours) {
  const int n = mesh.n_elements(), dim = mesh.dim;
  const auto& faces = element_faces(mesh.type());
  std::vector<std::pair<std::array<int, 4>, int>> keyed;
  keyed.reserve(static_cast<std::size_t>(n) * faces.size());
  for (int e = 0; e < n; ++e) {
    const int* v = mesh.element(e);
    for (const auto& local : faces) {
      std::array<int, 4> key = {-1, -1, -1, -1};
      for (int k = 0; k < dim; ++k) key[k] = v[local[k]];
      keyed.emplace_back(simplex_key(key, dim), e);
    }
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::vector<PetscInt>> adjacent(n);
  for (std::size_t k = 0; k + 1 < keyed.size(); ++k)
    if (keyed[k].first == keyed[k + 1].first) {
      adjacent[keyed[k].second].push_back(keyed[k + 1].second);
      adjacent[keyed[k + 1].second].push_back(keyed[k].second);
    }
  offsets.assign(1, 0);
  neighbours.clear();
  for (int e = 0; e < n; ++e) {
    std::sort(adjacent[e].begin(), adjacent[e].end());
    neighbours.insert(neighbours.end(), adjacent[e].begin(), adjacent[e].end());
    offsets.push_back(static_cast<PetscInt>(neighbours.size()));
  }
}

}  // namespace

std::vector<int> partition_elements(const Mesh& mesh, int parts) {
  const int n = mesh.n_elements();
  std::vector<int> part(n, 0);
  if (parts <= 1 || n == 0) return part;
  if (n < parts) {  // fewer elements than ranks: one each, the last ranks empty
    for (int e = 0; e < n; ++e) part[e] = e;
    return part;
  }
  std::vector<PetscInt> offsets, neighbours;
  dual_graph(mesh, offsets, neighbours);
  // MATMPIADJ takes arrays PETSc allocated.
  PetscInt *ia = nullptr, *ja = nullptr;
  check_coarse_partition(PetscMalloc1(offsets.size(), &ia), "PetscMalloc1");
  check_coarse_partition(PetscMalloc1(std::max<std::size_t>(neighbours.size(), 1), &ja), "PetscMalloc1");
  std::copy(offsets.begin(), offsets.end(), ia);
  std::copy(neighbours.begin(), neighbours.end(), ja);
  Mat adjacency = nullptr;
  MatPartitioning partitioning = nullptr;
  IS assignment = nullptr;
  PetscErrorCode code = MatCreateMPIAdj(PETSC_COMM_SELF, n, n, ia, ja, nullptr, &adjacency);
  const char* step = "MatCreateMPIAdj";
  if (!code) code = MatPartitioningCreate(PETSC_COMM_SELF, &partitioning), step = "MatPartitioningCreate";
  if (!code) code = MatPartitioningSetAdjacency(partitioning, adjacency), step = "MatPartitioningSetAdjacency";
  if (!code) code = MatPartitioningSetNParts(partitioning, parts), step = "MatPartitioningSetNParts";
  if (!code) code = MatPartitioningSetType(partitioning, MATPARTITIONINGPTSCOTCH), step = "MatPartitioningSetType";
  if (!code) code = MatPartitioningSetFromOptions(partitioning), step = "MatPartitioningSetFromOptions";
  if (!code) code = MatPartitioningApply(partitioning, &assignment), step = "MatPartitioningApply";
  const PetscInt* indices = nullptr;
  if (!code) code = ISGetIndices(assignment, &indices), step = "ISGetIndices";
  if (!code) {
    for (int e = 0; e < n; ++e) part[e] = static_cast<int>(indices[e]);
    ISRestoreIndices(assignment, &indices);
  }
  if (assignment) ISDestroy(&assignment);
  if (partitioning) MatPartitioningDestroy(&partitioning);
  if (adjacency)
    MatDestroy(&adjacency);
  else {
    PetscFree(ia);
    PetscFree(ja);
  }
  check_coarse_partition(code, step);
  return part;
}

}  // namespace contactqp::detail
