// A name for every node of a refined mesh that each rank computes alike, from where the node
// lies in the coarse mesh: the ranks refine their own parts of the coarse mesh
// (distributed_mesh.hpp), and a node on the border between two parts is made on both. The
// ranks then find each other's copies by name (a PetscSF over the names), never by position.
//
// Split n times, and given mid-edge nodes for order 2, a coarse simplex's nodes are exactly
// points of its barycentric lattice of denominator D = 2^n (·2 for order 2): a vertex is
// (D, 0, …), a new node the mean of its edge's two ends. A node's name is the coarse entity
// whose interior holds it (a vertex, an edge, a face, a cell: the vertices with nonzero weight)
// and its place on that entity's interior lattice, with the weights ordered by the vertices'
// coarse numbers, so that every simplex around the entity gives the same name:
//
//   vertices [0, V), then edges (D − 1 points each), faces (3D: (D − 1)(D − 2)/2), cells.
//
// Without refinement the name is the coarse node's number. No MPI here.
#pragma once

#include <array>
#include <vector>

#include "contactqp/mesh.hpp"
#include "mesh/refine.hpp"

namespace contactqp::detail {

// The edges and faces of a coarse mesh, numbered once (on the rank that meshes it), and each
// element's: edge k of an element joins its vertices kSimplexEdges[k]; face k (3D) is the one
// opposite its vertex k.
struct CoarseEntities {
  int dim = 3;
  long long n_vertices = 0, n_edges = 0, n_faces = 0, n_cells = 0;  // faces: 3D only
  std::vector<int> element_edges;                                   // 3 (2D) or 6 (3D) per element
  std::vector<int> element_faces;                                   // 4 per element (3D); empty in 2D
};
int edges_per_simplex(int dim);                             // 3 or 6
const std::array<int, 2>& simplex_edge(int k);              // the vertices of edge k (the 10-node tetrahedron's order)
std::array<int, 3> simplex_face(int k);                     // 3D: the vertices of the face opposite vertex k, ascending
CoarseEntities number_coarse_entities(const Mesh& coarse);  // vertices: the first dim + 1 nodes of each element

// A simplex (or a face) named by its n ≤ 4 vertices, ascending, the rest −1: the same key
// whichever element lists it.
std::array<int, 4> simplex_key(std::array<int, 4> vertices, int n);

// The names of one rank's refined nodes. The coarse part is given by its elements' global
// numbers of vertices, edges, faces and cells (`vertex[v]` for local coarse node v).
class CoarseLattice {
 public:
  // `refinements` splits, then mid-edge nodes when `order` is 2; `totals` the whole coarse
  // mesh's counts (only they are read from it).
  CoarseLattice(int dim, int refinements, int order, const CoarseEntities& totals);

  // How many names there are (a name is in [0, size())); names need not all be used.
  long long size() const { return size_; }

  // The name of each node of `refined` = refine_coarse(part) with `parents` from it.
  // `part_vertex[v]` is the global number of the part's node v (a vertex), `part_cell[e]`,
  // `part_edges` and `part_faces` the global numbers of element e's cell, edges and faces (as
  // CoarseEntities lays them out). Without refinements every node is a vertex: its name is
  // part_vertex (P2 coarse nodes included).
  std::vector<long long> names(const Mesh& part, const std::vector<int>& part_vertex, const std::vector<int>& part_cell,
                               const std::vector<int>& part_edges, const std::vector<int>& part_faces,
                               const NodeParents& parents) const;

 private:
  int dim_, refinements_, denominator_;
  long long n_vertices_, n_edges_, n_faces_;
  long long edge_offset_, face_offset_, cell_offset_, size_;
};

}  // namespace contactqp::detail
