// K and the prescribed displacements' share of f, assembled straight into K's compressed
// storage on two threads, with the same values bit for bit as a serial triplet assembly.
#pragma once

#include <Eigen/SparseCore>
#include <vector>

#include "contactqp/model.hpp"

namespace contactqp::detail {

// K over the free DOFs (in the DOF frames) from the elements marked in `elements` (empty: all;
// model.hpp's assemble_qp), and f −= K_free,prescribed · u_prescribed from every element.
void assemble_stiffness(const Model& model, const std::vector<char>& elements, Eigen::SparseMatrix<double>& K,
                        Eigen::VectorXd& f);

// K_e in the nodes' DOF frames: Tᵀ K_e T with T block-diagonal (the identity at most nodes);
// `v` the element's npe nodes.
Eigen::MatrixXd dof_frame_rotated(const Model& model, const int* v, int npe, Eigen::MatrixXd Ke);

// −K_free,prescribed · u_prescribed over the free DOFs, for the model's prescribed values: the
// prescribed displacements' share of f on its own, for a load step (apply_load_step). Only the
// elements with a non-zero prescribed DOF are visited. add_prescribed_forces() subtracts the
// same from f (a distributed run's part: this rank's elements, its local free DOFs).
Eigen::VectorXd prescribed_forces(const Model& model);
void add_prescribed_forces(const Model& model, Eigen::VectorXd& f);

}  // namespace contactqp::detail
