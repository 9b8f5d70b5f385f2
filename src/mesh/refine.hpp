// Uniform refinement of a 2D mesh: Gmsh meshes a coarser graded mesh (its time grows faster
// than the number of triangles, ours linearly) and each triangle is split into four here.
#pragma once

#include <functional>
#include <string>

#include "contactqp/mesh.hpp"

namespace contactqp::detail {

// Moves a new node on the boundary named `boundary` from the chord's midpoint `x` back onto
// the geometry (the identity for a straight side).
using SnapToBoundary = std::function<Eigen::Vector3d(const std::string& boundary, const Eigen::Vector3d& x)>;

// `mesh` (3-node triangles) with every triangle split into four by its mid-sides, `times`
// times, then given mid-side nodes when `order` is 2 (6-node triangles). New nodes of a named
// boundary's edges are snapped onto it; every boundary face is split with its edge, named
// regions keep their children, named points their nodes. The new nodes follow the old ones.
// Throws std::runtime_error (from orient()) when a snapped node leaves an element inverted.
Mesh refine_triangles(const Mesh& mesh, int times, int order, const SnapToBoundary& snap);

}  // namespace contactqp::detail
