// Rigid-body modes on the free DOFs. A prescribed DOF is removed from K, so the modes are not
// in K's null space (K is nonsingular): they are the near-null space, the smooth error that
// plain scalar AMG handles badly in elasticity, and PETSc's GAMG builds its coarse spaces from
// them (docs/linear-solvers.md). Three in 2D, six in 3D.
#include "rigid_body_modes.hpp"

#include "model_parts.hpp"

#include <algorithm>

namespace contactqp::detail {

Eigen::MatrixXd rigid_motions_at(int dim, const Eigen::Vector3d& position, const Eigen::Vector3d& centroid,
                                 double extent) {
  const Eigen::Vector3d x = (position - centroid) / extent;
  Eigen::MatrixXd global(dim, dim == 2 ? 3 : 6);
  if (dim == 2) {
    global << 1, 0, -x.y(), 0, 1, x.x();
  } else {
    // Translations, then rotations about x, y, z: ω × x.
    global << 1, 0, 0, 0, x.z(), -x.y(), 0, 1, 0, -x.z(), 0, x.x(), 0, 0, 1, x.y(), -x.x(), 0;
  }
  return global;
}

RigidBodyMotions::RigidBodyMotions(const Model& model) : model_(model) {
  const Mesh& mesh = model.mesh;
  const int n_nodes = mesh.n_nodes();
  for (int node = 0; node < n_nodes; ++node) centroid_ += mesh.nodes[node];
  if (n_nodes > 0) centroid_ /= n_nodes;
  extent_ = 0;
  for (int node = 0; node < n_nodes; ++node) extent_ = std::max(extent_, (mesh.nodes[node] - centroid_).norm());
  if (!(extent_ > 0)) extent_ = 1;
}

Eigen::MatrixXd RigidBodyMotions::at(int node) const {
  // Component c of a node's DOFs is along column c of its frame T: the value is (Tᵀ m)_c.
  return dof_frame(model_, node).transpose() *
         rigid_motions_at(model_.dim, model_.mesh.nodes[node], centroid_, extent_);
}

Eigen::MatrixXd rigid_body_modes(const Model& model) {
  const RigidBodyMotions motions(model);
  const int dim = model.dim;
  Eigen::MatrixXd modes = Eigen::MatrixXd::Zero(model.n_free, motions.n_modes());
  for (int node = 0; node < model.mesh.n_nodes(); ++node) {
    const Eigen::MatrixXd local = motions.at(node);
    for (int c = 0; c < dim; ++c) {
      const int row = model.free_index[dim * node + c];
      if (row >= 0) modes.row(row) = local.row(c);
    }
  }
  if (!model.rigid_rotations.empty()) {  // a turning surface: its translations and angles
    Eigen::MatrixXd at_dofs(dim * model.mesh.n_nodes(), motions.n_modes());
    for (int node = 0; node < model.mesh.n_nodes(); ++node) at_dofs.middleRows(dim * node, dim) = motions.at(node);
    fit_turning_surfaces(model, at_dofs, modes);
  }
  return modes;
}

}  // namespace contactqp::detail
