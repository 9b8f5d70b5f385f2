// Rigid-body modes on the free DOFs. A prescribed DOF is removed from K, so the modes are not
// in K's null space (K is nonsingular): they are the near-null space, the smooth error that
// plain scalar AMG handles badly in elasticity, and PETSc's GAMG builds its coarse spaces from
// them (docs/linear-solvers.md). 2D only for now; in 3D the same construction has six modes.
#include "rigid_body_modes.hpp"

#include <algorithm>

namespace contactqp::detail {

Eigen::MatrixXd rigid_body_modes(const Model& model) {
  const Mesh& mesh = model.mesh;
  const int n_nodes = mesh.n_nodes();
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (int node = 0; node < n_nodes; ++node) centroid += mesh.nodes[node];
  if (n_nodes > 0) centroid /= n_nodes;
  double extent = 0;
  for (int node = 0; node < n_nodes; ++node) extent = std::max(extent, (mesh.nodes[node] - centroid).norm());
  if (!(extent > 0)) extent = 1;

  Eigen::MatrixXd modes = Eigen::MatrixXd::Zero(model.n_free, 3);
  for (int node = 0; node < n_nodes; ++node) {
    const Eigen::Vector2d x = (mesh.nodes[node] - centroid) / extent;
    Eigen::Matrix<double, 2, 3> global;  // the three motions at this node, global x, y
    global << 1, 0, -x.y(),
              0, 1, x.x();
    // Component c of a node's DOFs is along column c of its frame T: the value is (Tᵀ m)_c.
    const Eigen::Matrix<double, 2, 3> local = dof_frame(model, node).transpose() * global;
    for (int c = 0; c < 2; ++c) {
      const int row = model.free_index[2 * node + c];
      if (row >= 0) modes.row(row) = local.row(c);
    }
  }
  return modes;
}

}  // namespace contactqp::detail
