// The system of one active-set step with the active rows fixed, without copying A:
//
//     W = D_F A D_F + D_X diag(A) (+ N),      rhs = D_F (b − A x_X) + diag(A) x_X
//
// (D_F, D_X the free and the fixed rows, x_X the fixed values): W x = rhs gives x = x_X on the
// fixed rows and A_FF x_F = b_F − A_FX x_X on the free ones. W is a shell around A (one
// product with A per product with W), and the fixed rows keep A's own diagonal, so Jacobi and
// Chebyshev built on A stay right for W (its diagonal is A's; its largest eigenvalue after
// Jacobi scaling is at most A's: the free block's interlaces A's, the fixed rows give 1).
// The preconditioner of W is z = D_F M D_F r + D_X r / diag(A) with M the hierarchy built on A
// once (its coarse levels kept right by truncation.hpp), symmetric positive definite as CG needs.
// N (couple()): small symmetric positive semidefinite blocks on free rows (3D friction's Newton
// term, bounded by the caller against A's diagonal so that the hierarchy built on A still fits
// W well); the preconditioner ignores N (smoother_op()).
// Pinned pairs (pin(), the combination mᵀx fixed): D_F generalised to the projection
// Π = I − D⁻¹m mᵀ/g along D⁻¹m (g = mᵀD⁻¹m, D = diag(A)), which the diagonal scaling makes
// orthogonal, and D_X diag(A) to m mᵀ/g:
//     W = Πᵀ A Π + m mᵀ/g,    preconditioner Π M Πᵀ + D⁻¹m mᵀD⁻¹/g,
// so that after Jacobi scaling a pin is a fixed row in rotated coordinates: W keeps A's
// diagonal scaling's bounds (the smoothers' Chebyshev intervals, estimated on A, still hold).
#pragma once

#include <petscksp.h>

#include <utility>
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
  // W without N, for the hierarchy's smoothers: the preconditioner stays the masked one of A,
  // symmetric positive definite whatever N (a smoother on W + N with eigenvalue bounds taken
  // on A was not: KSP_DIVERGED_INDEFINITE_PC on a one-node problem with N at A's diagonal).
  Mat smoother_op() const { return W_plain_; }
  Vec diagonal() const { return diagonal_; }

  // Makes `outer` (a PC of a KSP on W) the masked application of `inner` (a PC on A, set up).
  PetscErrorCode wrap(PC outer, PC inner);

  // The rows fixed from now on (local indices into A's ownership range), no other.
  void fix(const std::vector<PetscInt>& rows) { fixed_ = rows; }
  const std::vector<PetscInt>& fixed() const { return fixed_; }

  // Symmetric 2×2 blocks added to W on free rows (local indices; j −1: a 1×1 block a11 at i):
  // with 3D friction, the Newton term of each slipping contact row on its two tangential
  // variables (bound_pdas.cpp). None from now on with an empty list.
  struct Block {
    PetscInt i = -1, j = -1;
    double a11 = 0, a12 = 0, a22 = 0;
  };
  void couple(std::vector<Block> blocks) { blocks_ = std::move(blocks); }
  // Pairs of free rows (local indices i, j) on which one combination is fixed, m·(x_i, x_j) =
  // value: W and the preconditioner act on it as on a fixed row, on the rest of the pair as on
  // free rows. With 3D friction, a slipping row whose Newton term is stiff (near sticking)
  // slips along its direction only (bound_pdas.cpp). None from now on with an empty list.
  struct Pin {
    PetscInt i = -1, j = -1;
    double m0 = 0, m1 = 0, value = 0;
  };
  void pin(std::vector<Pin> pins) { pins_ = std::move(pins); }

  // rhs of the step and x's fixed rows set to `values` (one per fixed row). Collective.
  PetscErrorCode system(Vec b, const std::vector<double>& values, Vec x, Vec rhs);

 private:
  static PetscErrorCode multiply(Mat W, Vec x, Vec y);
  static PetscErrorCode multiply_plain(Mat W, Vec x, Vec y);
  PetscErrorCode product(Vec x, Vec y, bool with_blocks);
  static PetscErrorCode get_diagonal(Mat W, Vec d);
  static PetscErrorCode apply(PC pc, Vec r, Vec z);

  Mat A_ = nullptr, W_ = nullptr, W_plain_ = nullptr;
  // Separate work vectors: the inner preconditioner's smoother multiplies by W while apply()
  // still holds its masked input.
  Vec diagonal_ = nullptr, multiply_work_ = nullptr, apply_work_ = nullptr;
  PC inner_ = nullptr;
  std::vector<PetscInt> fixed_;
  std::vector<Block> blocks_;
  std::vector<Pin> pins_;
};

}  // namespace contactqp::detail
