// A QP without solution, and the evidence of it (solve.cpp looks when the certificate rejects an
// answer): rows that no u satisfies (a Farkas direction, as OSQP certifies primal infeasibility)
// and a free motion that the load drives and no row stops (a direction of recession, OSQP's dual
// infeasibility). K is then only positive semidefinite, which CHOLMOD need not notice: a
// singular K's last pivot is round-off and may come out positive, so its null space is found
// from eigenvalues, not pivots. docs/extremes.md, "Problems without a solution".
#pragma once

#include <Eigen/Core>

#include "contactqp/qp.hpp"
#include "qp/norms.hpp"

namespace contactqp::detail {

// An eigenvalue of K at most this fraction of ‖K‖∞ (which bounds the largest) counts as zero: a
// rigid mode's computed eigenvalue is round-off, ~1e-16 ‖K‖, and a grounding spring 1e-10 times
// weaker than the body would let the load move it 1e10 times further than the body deforms.
inline constexpr double kNullRelative = 1e-10;

// infinity_norm(K), max_i Σ_j |K_ij|, which bounds K's largest eigenvalue: norms.hpp.

// The length ‖u‖∞ beyond which only a (numerically) free motion explains u: the load (or the
// push that closes the gaps, ‖K‖∞‖g‖∞) over kNullRelative ‖K‖∞, the stiffness below which K
// counts as singular. +∞ when K = 0 (nothing measures a length). solve() examines a certified
// answer that long like a rejected one; a backend may stop an iterate that passes it.
double longest_carried_length(const QuadraticProgram& qp);

// Orthonormal columns spanning the eigenvectors of K (symmetric) whose eigenvalue is at most
// kNullRelative ‖K‖∞: dense eigenvalues up to a few hundred DOFs, else block inverse iteration
// with one CHOLMOD factorisation of K + σI and a Rayleigh–Ritz step. n × 0 when K is definite,
// or when K + σI has a negative pivot (K indefinite: not a convex QP, nothing to certify here).
// solve() looks for it only up to kNullSpaceMaxDofs DOFs: beyond, one more sparse Cholesky
// factorisation could exceed the memory of a run that chose an iterative solver of K.
inline constexpr int kNullSpaceMaxDofs = 200000;
Eigen::MatrixXd null_space_of(const SparseMatrix& K);

// d (‖d‖₂ = 1) in the span of R (K's null space) with B d ≤ 0 and fᵀd > 0, when one exists:
// then J(u + t d) = J(u) − t fᵀd for every t ≥ 0 on the feasible set, and the QP is unbounded.
// Found as the residual of min ‖RᵀBᵀλ − Rᵀf‖ over λ ≥ 0 (Farkas: the residual w is zero
// exactly when some λ ≥ 0 balances the load on every free mode, and else d = R w satisfies
// B d ≤ 0, fᵀd = ‖w‖² > 0). Frictionless problems only (friction's dissipation bounds a slide
// nonlinearly); empty when there is none.
VectorXd recession_direction(const QuadraticProgram& qp, const Eigen::MatrixXd& R);

// y ≥ 0 (‖y‖∞ = 1) with gᵀy < 0 and Bᵀy so small that any u with B u ≤ g would need
// ‖u‖₁ ≥ −gᵀy / ‖Bᵀy‖∞ > ‖g‖∞ / tol: rows that contradict each other. Found by the NNLS
// min ‖Bᵀy‖² + (gᵀy/‖g‖∞ + 1)² over y ≥ 0, which is zero exactly when B u ≤ g has no solution.
// Empty when there is none, when g ≥ 0 (u = 0 is feasible), m > kFarkasMaxRows or the NNLS
// needs more than kFarkasMaxSteps steps (each adds one row to the evidence).
inline constexpr int kFarkasMaxRows = 4000;
inline constexpr int kFarkasMaxSteps = 200;
VectorXd farkas_direction(const QuadraticProgram& qp, double tol);

}  // namespace contactqp::detail
