// The petsc backend's method, for the room's two callers: the backend's registration (K whole
// on every rank) and solve() of a ParQuadraticProgram (K in shares, par_qp.cpp).
#pragma once

#include "contactqp/qp.hpp"
#include "petsc_solver.hpp"

namespace contactqp::detail {

// The bound form of qp solved by PETSc; `layout` says where qp.K's rows are. Collective.
SolveResult solve_bound_form(const QuadraticProgram& qp, const MatrixLayout& layout, const SolveOptions& options);

}  // namespace contactqp::detail
