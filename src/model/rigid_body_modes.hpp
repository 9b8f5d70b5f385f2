// The rigid-body modes of the model on its free DOFs: the near-null space an algebraic
// multigrid preconditioner of K needs (QuadraticProgram::near_null_space).
#pragma once

#include <Eigen/Core>

#include "contactqp/model.hpp"

namespace contactqp::detail {

// n_free × 3 in 2D: translation along x, along y, and the rotation (−(y − y_c), x − x_c)/ℓ
// about the centroid (scaled by the extent ℓ, so the three columns are of one size), each
// expressed in the nodes' DOF frames (dof_frame()) and restricted to the free DOFs. n_free × 6
// in 3D: translations along x, y, z and the rotations e_k × (x − x_c)/ℓ about the three axes.
Eigen::MatrixXd rigid_body_modes(const Model& model);

// The modes' values at one point, dim × (3 or 6), global axes: the rows of rigid_body_modes()
// before the DOF frames, for the given centroid and extent.
Eigen::MatrixXd rigid_motions_at(int dim, const Eigen::Vector3d& position, const Eigen::Vector3d& centroid,
                                 double extent);

// The same motions at every node and component: the row of node n's component c is
// dim·n + c (in its DOF frame), prescribed components included.
class RigidBodyMotions {
 public:
  explicit RigidBodyMotions(const Model& model);
  int n_modes() const { return model_.dim == 2 ? 3 : 6; }
  Eigen::MatrixXd at(int node) const;  // dim × n_modes

 private:
  const Model& model_;
  Eigen::Vector3d centroid_ = Eigen::Vector3d::Zero();
  double extent_ = 1;
};

}  // namespace contactqp::detail
