// A multigrid hierarchy built once and kept consistent with a fine operator whose active rows
// are fixed: truncated multigrid (Kornhuber, Gräser–Sander–Kornhuber's TNNMG), here on an
// algebraic hierarchy.
//
// The fine operator of an active-set step is W = D_F A D_F + D_X diag(A) (masked_system.hpp:
// the free rows F as in A, the fixed rows X decoupled). Preconditioning W with the hierarchy
// of A — its coarse levels still coupling the fixed rows — doubled the CG iterations of a step
// (41 against 19 on a 3.1e5-DOF sphere, docs/petsc-measurements.md). With the same interpolations P_l the
// Galerkin operators of W are A_{l+1} = P_lᵀ A_l P_l starting from A_0 = W; when rows are fixed
// or released W changes only in their rows and columns, by ΔW, and so each coarse operator
// changes by ΔA_{l+1} = P_lᵀ ΔA_l P_l, which lives near those rows: a few thousand entries
// computed from the rows of P_l they touch. No set-up is repeated: the aggregates and
// interpolations stay; the smoothers re-read their diagonals and re-estimate their eigenvalue
// bounds on the changed operators, and the coarsest level is refactored (a few hundred rows).
#pragma once

#include <petscksp.h>

#include <vector>

namespace contactqp::detail {

class TruncatedHierarchy {
 public:
  TruncatedHierarchy() = default;
  TruncatedHierarchy(const TruncatedHierarchy&) = delete;
  TruncatedHierarchy& operator=(const TruncatedHierarchy&) = delete;

  // Takes the levels below the finest of pc, as set_up_multigrid() built it (the P1 level and
  // the AMG below it, or an AMG on A): every level whose operator is a Galerkin product and
  // whose smoother can be told it changed. A preconditioner without such levels (hypre,
  // Jacobi, an AMG other than GAMG or ML under the P1 level) leaves it inactive: its coarse
  // levels then stay those of A. A is the unmasked fine operator. Collective.
  PetscErrorCode collect(PC pc, Mat A);
  bool active() const { return !operators_.empty(); }

  // Makes the coarse operators those of W with `fixed` (this rank's rows, local indices into
  // A's ownership range) fixed and every other row free. Collective.
  PetscErrorCode fix_rows(const std::vector<PetscInt>& fixed);

  double update_seconds() const { return update_seconds_; }

 private:
  Mat A_ = nullptr;
  PetscInt first_ = 0, end_ = 0;
  std::vector<Mat> transfers_;  // transfers_[l]: level l+1 → level l (level 0 the fine one)
  std::vector<Mat> operators_;  // operators_[l]: level l+1's operator, changed in place
  std::vector<KSP> smoothers_;  // the solvers on those operators, told after each change
  std::vector<char> free_;      // this rank's fine rows: free now
  double update_seconds_ = 0;
};

}  // namespace contactqp::detail
