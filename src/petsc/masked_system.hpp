// The system of one active-set step with the active rows fixed, without copying A:
//
//     W = D_F A D_F + D_X diag(A),      rhs = D_F (b − A x_X) + diag(A) x_X
//
// (D_F, D_X the free and the fixed rows, x_X the fixed values): W x = rhs gives x = x_X on the
// fixed rows and A_FF x_F = b_F − A_FX x_X on the free ones. W is a shell around A (one
// product with A per product with W), and the fixed rows keep A's own diagonal, so Jacobi and
// Chebyshev built on A stay right for W (its diagonal is A's; its largest eigenvalue after
// Jacobi scaling is at most A's: the free block's interlaces A's, the fixed rows give 1).
// The preconditioner of W is z = D_F M D_F r + D_X r / diag(A) with M the hierarchy built on A
// once (its coarse levels kept right by truncation.hpp), symmetric positive definite as CG needs.
#pragma once

#include <petscksp.h>

#include <vector>

namespace contactqp::detail {

class MaskedSystem {
 public:
  MaskedSystem() = default;
  MaskedSystem(const MaskedSystem&) = delete;
  MaskedSystem& operator=(const MaskedSystem&) = delete;
  ~MaskedSystem();

  // The shell W around A (not owned; A must outlive this). Collective.
  PetscErrorCode create(Mat A);
  Mat op() const { return W_; }
  Vec diagonal() const { return diagonal_; }

  // Makes `outer` (a PC of a KSP on W) the masked application of `inner` (a PC on A, set up).
  PetscErrorCode wrap(PC outer, PC inner);

  // The rows fixed from now on (local indices into A's ownership range), no other.
  void fix(const std::vector<PetscInt>& rows) { fixed_ = rows; }
  const std::vector<PetscInt>& fixed() const { return fixed_; }

  // rhs of the step and x's fixed rows set to `values` (one per fixed row). Collective.
  PetscErrorCode system(Vec b, const std::vector<double>& values, Vec x, Vec rhs);

 private:
  static PetscErrorCode multiply(Mat W, Vec x, Vec y);
  static PetscErrorCode get_diagonal(Mat W, Vec d);
  static PetscErrorCode apply(PC pc, Vec r, Vec z);

  Mat A_ = nullptr, W_ = nullptr;
  // Separate work vectors: the inner preconditioner's smoother multiplies by W while apply()
  // still holds its masked input.
  Vec diagonal_ = nullptr, multiply_work_ = nullptr, apply_work_ = nullptr;
  PC inner_ = nullptr;
  std::vector<PetscInt> fixed_;
};

}  // namespace contactqp::detail
