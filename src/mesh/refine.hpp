// Uniform refinement of a mesh: Gmsh meshes a coarser graded mesh (its time grows faster than
// the number of elements, ours linearly) and each triangle is split into four here (2D), each
// tetrahedron into eight (3D).
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "contactqp/mesh.hpp"

namespace contactqp::detail {

// Moves a new node on the boundary named `boundary` from the chord's midpoint `x` back onto
// the geometry (the identity for a straight side or a flat face).
using SnapToBoundary = std::function<Eigen::Vector3d(const std::string& boundary, const Eigen::Vector3d& x)>;

// The two nodes whose edge each new node of a refinement halves: entry k is node n + k, n the
// nodes of the mesh refined. Nodes keep their indices from one split to the next and through
// the mid-edge nodes of order 2, so one list covers every level; the distributed mesh
// (src/distributed/) names each node by where it lies in the coarse mesh from it.
using NodeParents = std::vector<std::array<int, 2>>;

// `mesh` (3-node triangles) with every triangle split into four by its mid-sides, `times`
// times, then given mid-side nodes when `order` is 2 (6-node triangles). New nodes of a named
// boundary's edges are snapped onto it; every boundary face is split with its edge, named
// regions keep their children, named points their nodes. The new nodes follow the old ones.
// Throws std::runtime_error (from orient()) when a snapped node leaves an element inverted.
// `parents`, when given, receives the parents of every new node.
Mesh refine_triangles(const Mesh& mesh, int times, int order, const SnapToBoundary& snap,
                      NodeParents* parents = nullptr);

// The same in 3D: `mesh` (4-node tetrahedra) with every tetrahedron split into eight by its
// mid-edges (Bey's red refinement: four corner tetrahedra, and the inner octahedron cut along
// its shortest diagonal into four), `times` times, then given mid-edge nodes when `order` is 2
// (10-node tetrahedra, our node order). Every boundary triangle is split into four with the
// same mid-edge nodes (6-node triangles at order 2); the new nodes of its edges are snapped.
// Region e's children are 8e … 8e + 7. Throws std::runtime_error as refine_triangles does.
Mesh refine_tetrahedra(const Mesh& mesh, int times, int order, const SnapToBoundary& snap,
                       NodeParents* parents = nullptr);

// A body's mesh as Gmsh makes it, and how it becomes the body's mesh: the generated shapes
// mesh coarse and refine (body.mesh.refinements); a distributed run (src/distributed/) sends
// each rank its part of the coarse mesh and refines it there.
struct CoarseMesh {
  Mesh mesh;            // 3-node triangles or 4-node tetrahedra when refinements > 0
  int refinements = 0;  // each triangle split into 4, each tetrahedron into 8, this many times
  int order = 1;        // of the refined mesh: 2 adds mid-edge nodes after the splits
  SnapToBoundary snap;  // puts a refinement's new boundary nodes back on the geometry (coarse coordinates)
  double scale = 1;     // the refined mesh's coordinates times this are the body's
};

// The simplices one simplex of dimension `dim` becomes in `refinements` splits: 2^(dim·n)
// (a boundary edge 2^n, a triangle 4^n, a tetrahedron 8^n).
long long refined_children(int dim, int refinements);

// `part` (coarse.mesh or some of its elements, with its boundary faces) refined as `coarse`
// says and scaled; with no refinements, `part` itself. Children of element e are
// e·f … e·f + f − 1 (f = refined_children(dim, n)), those of boundary face k of a boundary
// k·g … (g = refined_children(dim − 1, n)): a part's own elements are found among them.
Mesh refine_coarse(const CoarseMesh& coarse, const Mesh& part, NodeParents* parents = nullptr);

}  // namespace contactqp::detail
