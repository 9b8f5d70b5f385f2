// K and the prescribed displacements' share of f, assembled straight into K's compressed
// storage on two threads, with the same values bit for bit as a serial triplet assembly.
#pragma once

#include <Eigen/SparseCore>

#include "contactqp/model.hpp"

namespace contactqp::detail {

// K over the free DOFs (in the DOF frames), and f −= K_free,prescribed · u_prescribed.
void assemble_stiffness(const Model& model, Eigen::SparseMatrix<double>& K, Eigen::VectorXd& f);

}  // namespace contactqp::detail
