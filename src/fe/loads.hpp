// Force loads on a mesh (loads.cpp): the consistent nodal forces of a scene's loads and the
// nodes its point loads act at. The model's steps (model/model_parts.hpp) build on them.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "contactqp/mesh.hpp"
#include "contactqp/scene.hpp"

namespace contactqp::detail {

// The consistent nodal forces (dim·n_nodes, global axes, for the body's thickness in 2D)
// of the force loads of `scene` on `mesh` — both already in the global frame. Point loads act
// at `point_nodes[l]` for load l (chosen in the scene's own frame, see point_load_nodes).
Eigen::VectorXd nodal_forces(const Scene& scene, const Mesh& mesh, const std::vector<int>& point_nodes);

// The node each point load acts at (−1 for other loads): the nearest node to
// its `at`, or its named point. Adds a warning when that node is far from `at`.
std::vector<int> point_load_nodes(const Scene& scene, const Mesh& mesh, std::vector<std::string>& warnings);

// The centroid of a boundary of `mesh` (its faces' measure-weighted mean point).
Eigen::Vector3d boundary_centroid(const Mesh& mesh, const std::string& boundary);

}  // namespace contactqp::detail
