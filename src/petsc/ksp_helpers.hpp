// Small pieces the room's KSP solvers share (petsc_solver.cpp, petsc_bound_qp.cpp,
// bound_pdas.cpp, src/distributed/): their stopping rule, the words of a failed solve, a
// matrix's bytes, and a distributed vector back on every rank.
#pragma once

#include <petscksp.h>

#include <Eigen/Core>
#include <algorithm>
#include <sstream>
#include <string>

#include "petsc_matrix.hpp"

namespace contactqp::detail {

// The inner stopping rule (docs/linear-solvers.md): ‖b − A x‖₂ ≤ kInnerFraction · tol · ‖b‖∞.
// The certificate's stationarity is ‖Ku − f + Bᵀλ‖∞ / F with F ≥ max(‖f‖∞, ‖Bᵀλ‖∞), and a
// backend's right-hand side b = f − Bᵀλ has ‖b‖∞ ≤ 2F; with ‖r‖∞ ≤ ‖r‖₂ the solve leaves a
// stationarity of at most 2 · kInnerFraction · tol = tol / 10, so the certificate holds at tol.
inline constexpr double kInnerFraction = 1e-3;
// Iterations of one KSP solve before it counts as not converging (-ksp_max_it overrides).
inline constexpr PetscInt kMaxKrylovIterations = 10000;

// Round-off: a residual this small relative to ‖A‖∞‖x‖∞ is as good as a backward-stable direct
// solve gets, whatever the rule asks (CG then stagnates instead of converging).
constexpr double kRoundOff = 100 * 2.220446049250313e-16;

// The stopping rule every CG solve of the room ends with, once KSPConvergedDefault has had its
// say (divergence, -ksp_max_it, a user's -ksp_rtol or -ksp_atol): converged when ‖r‖ ≤ target,
// or ≤ the round-off floor kRoundOff·‖A‖∞·‖x‖∞. The floor needs ‖x‖∞ (free for CG: its iterate
// is stored), so it is looked at only near the target.
inline PetscErrorCode inner_stopping_rule(KSP ksp, PetscReal rnorm, double target, double A_norm,
                                          KSPConvergedReason* reason) {
  if (*reason != KSP_CONVERGED_ITERATING) return 0;
  if (rnorm > target && rnorm <= 1e6 * target) {
    Vec x = nullptr;
    PetscReal x_norm = 0;
    PetscCall(KSPBuildSolution(ksp, nullptr, &x));
    PetscCall(VecNorm(x, NORM_INFINITY, &x_norm));
    target = std::max(target, kRoundOff * A_norm * x_norm);
  }
  if (rnorm <= target) *reason = KSP_CONVERGED_ATOL;
  return 0;
}

// The bytes of an AIJ matrix's rows on this rank: a value and a column index per entry, a row
// pointer per row.
inline double matrix_bytes(Mat M) {
  MatInfo info;
  PetscInt rows = 0, columns = 0;
  if (MatGetInfo(M, MAT_LOCAL, &info) || MatGetLocalSize(M, &rows, &columns)) return 0;
  return info.nz_allocated * (sizeof(PetscScalar) + sizeof(PetscInt)) + (rows + 1.0) * sizeof(PetscInt);
}

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
