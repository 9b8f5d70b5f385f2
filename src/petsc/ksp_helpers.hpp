// Small pieces the room's KSP solvers share (petsc_solver.cpp, petsc_bound_qp.cpp,
// bound_pdas.cpp): the words of a failed solve, and a distributed vector back on every rank.
#pragma once

#include <petscksp.h>

#include <Eigen/Core>
#include <sstream>
#include <string>

#include "petsc_matrix.hpp"

namespace contactqp::detail {

// A number in a message, to four significant digits ("2.9e-11", not to_string's "0.000000").
inline std::string number_text(double x) {
  std::ostringstream text;
  text.precision(4);
  text << x;
  return text.str();
}

// "the PETSc KSP did not converge: KSP_DIVERGED_ITS after 10000 iterations at residual ...".
inline std::string reason_text(KSP ksp, PetscInt iterations, double target) {
  const char* name = nullptr;
  KSPGetConvergedReasonString(ksp, &name);  // the name without the enum's KSP_ prefix
  PetscReal residual = 0;
  KSPGetResidualNorm(ksp, &residual);
  std::ostringstream text;
  text.precision(3);
  text << "the PETSc KSP did not converge: KSP_" << (name ? name : "unknown reason") << " after " << iterations
       << " iterations at residual " << residual << " (target " << target << ")";
  return text.str();
}

// The whole of the distributed x on every rank, in the variables' order (`to_all` scatters x
// into x_all, VecScatterCreateToAll). Collective.
inline Eigen::VectorXd gather_whole(VecScatter to_all, Vec x, Vec x_all, const RowOrder& order, int n) {
  VecScatterBegin(to_all, x, x_all, INSERT_VALUES, SCATTER_FORWARD);
  VecScatterEnd(to_all, x, x_all, INSERT_VALUES, SCATTER_FORWARD);
  const PetscScalar* all = nullptr;
  VecGetArrayRead(x_all, &all);
  Eigen::VectorXd out = order.to_dofs(all, n);
  VecRestoreArrayRead(x_all, &all);
  return out;
}

}  // namespace contactqp::detail
