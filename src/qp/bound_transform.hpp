// The petsc backend's change of variables at one node (docs/petsc-design.md, "The bound form"): the
// node's contact rows become bounds on single variables. Shared by the serial bound form
// (solvers/bound_form.cpp) and the distributed one (src/distributed/), which applies it to each
// element's matrix.
#pragma once

#include <Eigen/Core>

namespace contactqp::detail {

// `rows` (r × c): the node's rows of B on its c columns. On success, T (c × c) is those rows
// followed by an orthonormal basis of the complement of their span, and Q = T⁻¹, so that with
// v = T u_C row k of B u ≤ g is v_k ≤ g_k. False when the rows are linearly dependent (or
// r > c): the bound form needs independent rows at each node.
bool bound_transform(const Eigen::MatrixXd& rows, Eigen::MatrixXd& T, Eigen::MatrixXd& Q);

}  // namespace contactqp::detail
