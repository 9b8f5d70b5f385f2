// The model of a body under mpirun, each rank holding its part of it (docs/petsc-design.md,
// "Distributed runs"): its part of the mesh (distributed_mesh.hpp), the boundary conditions,
// loads and contact candidates of its nodes, and the numbering that joins the parts — each free
// DOF a row of the distributed matrix, each candidate of a rank's own nodes a contact row.
//
// Quantities a node gets from the faces and elements around it (which boundaries it lies on, a
// candidate's normal and tributary area) are added up over the ranks that hold it first, so
// that every rank decides alike about a node it shares with another.
#pragma once

#include <petscsys.h>

#include <functional>
#include <string>
#include <vector>

#include "contactqp/model.hpp"
#include "distributed_mesh.hpp"

namespace contactqp::detail {

struct DistributedModel {
  // This rank's part as a Model (the serial FE code runs on it as it is): the scene, the mesh
  // part (its own nodes first), the prescribed DOFs and frames of its nodes, the nodal forces
  // of its own faces and elements (summed over the ranks in the matrix' right-hand side), and
  // the candidates at all its nodes, its own nodes' first. free_index numbers the free DOFs of
  // all its nodes, its own nodes' first.
  Model local;
  std::vector<BoundaryFace> outer;  // the whole body's outer faces among this part's (MeshPart)
  int n_owned = 0;                  // nodes 0 … n_owned − 1 are this rank's
  std::vector<int> global_node;
  long long n_global_nodes = 0, n_global_elements = 0;
  SharedNodes shared;

  // Free DOFs: local free indices 0 … n_own_dofs − 1 are this rank's own.
  int n_own_dofs = 0;
  long long n_global_dofs = 0;
  // Rows of the distributed matrix (the solver's block size dim): every node with a free DOF has
  // its dim rows, consecutive, on its owner, its prescribed DOFs' rows too (they hold only their
  // diagonal); nodes whose DOFs are all prescribed have none. This rank's rows are
  // first_row … first_row + n_own_rows − 1.
  PetscInt first_row = 0;
  int n_own_rows = 0;
  long long n_global_rows = 0;
  std::vector<PetscInt> node_row;     // the first row of each node, −1 without a free DOF
  std::vector<PetscInt> row_of_free;  // the row of each local free DOF
  // The place of an own free DOF among this rank's rows (a PETSc vector's local array).
  int local_row(int free) const { return static_cast<int>(row_of_free[free] - first_row); }

  // Contact rows: local.candidates[0 … n_own_candidates − 1] are at this rank's nodes and are
  // its rows first_candidate … of the whole B u ≤ g.
  int n_own_candidates = 0;
  PetscInt first_candidate = 0;
  long long n_global_candidates = 0;

  // The boundaries each node lies on (whichever rank holds the face): bit b % 31 of word b / 31
  // for boundary_names[b].
  std::vector<std::string> boundary_names;
  int mask_words = 1;
  std::vector<int> boundary_mask;                                // mask_words per node
  std::vector<int> nodes_of(const std::string& boundary) const;  // ascending local nodes
  bool on_boundary(int node, const std::string& boundary) const;
};

// Collective: distributes the mesh, then builds every rank's part of the model. Bad input is
// thrown on the rank that finds it; the others meet it at the next checkpoint() and throw
// FailedElsewhere (run/phases.hpp). One-body scenes only. With load steps the part keeps each
// load's share (Model::load_shares), as build_model() does.
// `on_phase`, when given, is called with "model" once the mesh is distributed.
DistributedModel build_distributed_model(const Scene& scene, const BuildOptions& options,
                                         const std::function<void(const char* phase)>& on_phase = {});

}  // namespace contactqp::detail
