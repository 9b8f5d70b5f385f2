// A body's mesh under mpirun, no rank holding it whole (docs/petsc-design.md, "Distributed runs").
//
// Rank 0 meshes the coarse body (Gmsh; body.mesh.refinements makes it 4^n or 8^n times
// coarser than the body's mesh) and PT-Scotch splits its elements into one part per rank. Each
// rank receives its part with a layer of ghost elements (every coarse element that shares a
// vertex with it), refines all of it with the serial code, and keeps the children of its own
// elements: the ghosts carry the boundary faces that decide which new nodes are snapped onto
// the geometry, so the kept elements are exactly the serial refinement's, node for node. Where
// two parts meet, both ranks make the same nodes; the coarse lattice names them
// (coarse_lattice.hpp) and a PetscSF over the names decides who owns each (the lowest rank
// holding it) and gives the global numbering. Without refinements (a Gmsh file, or a shape
// meshed directly) the coarse mesh is the body's and only its elements are distributed.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "contactqp/model.hpp"
#include "shared_nodes.hpp"

namespace contactqp::detail {

struct MeshPart {
  // This rank's elements (the refined children of its coarse elements), their nodes — its own
  // first — and the boundary faces of its elements, boundaries named as in the whole mesh (a
  // boundary with no face here is present and empty). Regions hold this rank's elements,
  // points its nodes.
  Mesh mesh;
  // The faces of the whole body's outer boundary that belong to this rank's elements (what
  // outer_boundary() gives for the whole mesh; this part's own outer boundary also has the faces
  // it shares with other ranks' parts).
  std::vector<BoundaryFace> outer;
  int n_owned = 0;               // nodes 0 … n_owned − 1 are this rank's
  std::vector<int> global_node;  // each node's number in the whole mesh (rank r's after those of ranks < r)
  int first_global_node = 0;     // the global number of node 0: own nodes are consecutive
  long long n_global_nodes = 0, n_global_elements = 0;
  SharedNodes shared;  // sums and maxima over the ranks holding a node
};

// Collective. Bad input found while meshing is thrown on rank 0; the others meet it at a
// checkpoint() and throw FailedElsewhere (run/phases.hpp). The scene's max_gap is the model's
// candidate distance. `check_coarse`, when given, runs on rank 0 with the coarse mesh before it
// is split (the checks that need the whole body: names, conflicting conditions, rigid motions).
MeshPart distribute_body_mesh(const Scene& scene, double max_gap, const BuildOptions& options,
                              const std::function<void(const Mesh& coarse)>& check_coarse = {});

}  // namespace contactqp::detail
