// The split of a coarse mesh's elements between the ranks (distributed_mesh.hpp), made on the
// rank that meshed it: PT-Scotch through PETSc's MatPartitioning on the elements' dual graph
// (elements that share a face are neighbours), as the K partition of docs/petsc-design.md is made on
// the node graph. -mat_partitioning_type in the PETSc options chooses another partitioner.
#pragma once

#include <vector>

#include "contactqp/mesh.hpp"

namespace contactqp::detail {

// The part (0 … parts − 1) of each element of `mesh`, each part non-empty when there are enough
// elements. Not collective: PETSc on PETSC_COMM_SELF. Throws std::runtime_error when PETSc fails.
std::vector<int> partition_elements(const Mesh& mesh, int parts);

}  // namespace contactqp::detail
