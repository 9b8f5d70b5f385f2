// Uniform refinement of a mesh: Gmsh meshes a coarser graded mesh (its time grows faster than
// the number of elements, ours linearly) and each triangle is split into four here (2D), each
// tetrahedron into eight (3D).
#pragma once

#include <functional>
#include <string>

#include "contactqp/mesh.hpp"

namespace contactqp::detail {

// Moves a new node on the boundary named `boundary` from the chord's midpoint `x` back onto
// the geometry (the identity for a straight side or a flat face).
using SnapToBoundary = std::function<Eigen::Vector3d(const std::string& boundary, const Eigen::Vector3d& x)>;

// `mesh` (3-node triangles) with every triangle split into four by its mid-sides, `times`
// times, then given mid-side nodes when `order` is 2 (6-node triangles). New nodes of a named
// boundary's edges are snapped onto it; every boundary face is split with its edge, named
// regions keep their children, named points their nodes. The new nodes follow the old ones.
// Throws std::runtime_error (from orient()) when a snapped node leaves an element inverted.
Mesh refine_triangles(const Mesh& mesh, int times, int order, const SnapToBoundary& snap);

// The same in 3D: `mesh` (4-node tetrahedra) with every tetrahedron split into eight by its
// mid-edges (Bey's red refinement: four corner tetrahedra, and the inner octahedron cut along
// its shortest diagonal into four), `times` times, then given mid-edge nodes when `order` is 2
// (10-node tetrahedra, our node order). Every boundary triangle is split into four with the
// same mid-edge nodes (6-node triangles at order 2); the new nodes of its edges are snapped.
// Region e's children are 8e … 8e + 7. Throws std::runtime_error as refine_triangles does.
Mesh refine_tetrahedra(const Mesh& mesh, int times, int order, const SnapToBoundary& snap);

}  // namespace contactqp::detail
