// The contact QP as a bound-constrained QP (the petsc backend's form, docs/petsc-design.md).
//
// The rows of B fall into groups that share no column (one group per candidate node: its one
// or two rows at its free DOFs). Each group's DOFs u_C get new variables v_C = T u_C, where T's
// first rows are the group's rows of B and the rest an orthonormal basis of their complement;
// then row i of B u ≤ g is the bound v_i ≤ g_i on one variable. With u = Q v (Q = T⁻¹ per group,
// the identity elsewhere) the QP becomes  min ½ vᵀ(QᵀKQ)v − (Qᵀf)ᵀv,  still positive definite,
// and a rigid-body mode r of K becomes Q⁻¹ r. A node with one row has an orthogonal T.
//
// Rows that share DOFs without sharing all of them (a node against another body's face: its
// own DOFs and the face's, which its neighbours' rows touch too) are not made one dense group:
// each such row takes new variables on its own DOFs, T = [its part of the row; the complement],
// the shared DOFs keeping theirs, so that Q stays as sparse as B and QᵀKQ about as sparse as K.
#pragma once

#include <string>

#include "contactqp/qp.hpp"
#include "petsc_bound_qp.hpp"
#include "petsc_solver.hpp"

namespace contactqp::detail {

struct BoundForm {
  SparseMatrix Q;   // u = Q v
  BoundQp problem;  // bounded[i] is the variable of row i of B, upper = g
};

// False with `message` set when a group's rows are linearly dependent (the bound form needs
// independent rows at each node; the other backends accept such rows). `layout` says where
// qp.K's rows are (whole, or a rank's share), and so where A's are: v is indexed like u.
// Without `with_operator`, no A, near-null space or P1 level (problem.A etc. empty): what a
// solve that continues a chain needs (petsc_bound_qp.hpp, BoundQpChain), whose A is in PETSc.
bool make_bound_form(const QuadraticProgram& qp, const MatrixLayout& layout, BoundForm& form, std::string& message,
                     bool with_operator = true);

}  // namespace contactqp::detail
