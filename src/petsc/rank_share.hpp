// Under mpirun with the petsc backend, which elements each rank assembles (par_qp.hpp's
// RankShare, docs/petsc-design.md): the mesh's nodes are partitioned (PT-Scotch through PETSc), the
// DOFs of each part get consecutive rows of the distributed matrix, and a rank assembles the
// elements whose first free DOF's row lies in its block of rows (PETSc's split into contiguous
// blocks), so that what it adds is mostly its own rows.
#pragma once

#include <vector>

#include "contactqp/model.hpp"
#include "contactqp/petsc/par_qp.hpp"

namespace contactqp::detail {

// The row of each free DOF in the distributed matrix: the DOFs of part 0 of a partition of the
// mesh's node graph into `ranks` parts first, in their own order, then part 1's, ... The same
// on every rank. Collective. Empty when the partition failed.
std::vector<int> distributed_rows(const Model& model, int ranks);

// Throws on every rank when the ranks' models differ (each rank meshed the scene itself: the
// same input gives the same mesh, and a different one would leave the collective steps waiting
// on different sizes or sum shares of different K's): nodes, elements, free DOFs and a checksum
// of the coordinates agree exactly. Collective; nothing to check on one process.
void check_same_model_on_every_rank(const Model& model);

// 1 for each element this rank adds to K: all of them for one rank; else those whose first
// free DOF's row (distributed_row, or the DOF itself when empty) is in the rank's block. An
// element without free DOFs adds nothing anywhere.
std::vector<char> owned_elements(const Model& model, const RankShare& share, const std::vector<int>& distributed_row);

}  // namespace contactqp::detail
