// Spectrum estimates of the condensed contact operator S = B K⁻¹ Bᵀ (m × m, symmetric
// positive semidefinite), applied matrix-free: S v = B (K⁻¹ (Bᵀ v)), one solve with K
// (its LinearSolver) per application. S is never formed.
#pragma once

#include <vector>

#include "contactqp/linear_solver.hpp"
#include "contactqp/qp.hpp"

namespace contactqp::detail {

struct SpectrumEstimate {
  double lambda_min = 0;   // estimate of the smallest eigenvalue of S on the chosen rows (0 when none)
  double lambda_max = 0;   // estimate of the largest eigenvalue (0 when none)
  int rows = 0;            // how many rows of B the block covers
  int applications = 0;    // products with S, i.e. solves with K, spent on the estimate
  bool converged = false;  // both extreme Ritz values settled (or the Krylov space became invariant)
  double seconds = 0;
};

// Lanczos with full reorthogonalisation on the principal block S_R = B_R K⁻¹ B_Rᵀ of the rows
// R (`rows`; every row when empty). The extreme Ritz values approach λ_max from below and
// λ_min from above; the iteration stops when, over the last few steps, λ_max has changed by
// less than `rel_tol_max` and λ_min by less than `rel_tol_min` (relative), when the Krylov
// space becomes invariant (exact at |R| steps), or after `max_steps` products.
SpectrumEstimate estimate_spectrum(const QuadraticProgram& qp, const LinearSolver& K_factor,
                                   const std::vector<int>& rows = {}, int max_steps = 400, double rel_tol_max = 1e-6,
                                   double rel_tol_min = 1e-3);
// The same for the rows of any C in place of B (e.g. the stacked [B; T] of a frictional problem).
SpectrumEstimate estimate_spectrum(const SparseMatrix& C, const LinearSolver& K_factor,
                                   const std::vector<int>& rows = {}, int max_steps = 400, double rel_tol_max = 1e-6,
                                   double rel_tol_min = 1e-3);

// λ_max(S) on every row (kept for callers that need only the bound ρ < 2/λ_max(S)).
SpectrumEstimate estimate_lambda_max(const QuadraticProgram& qp, const LinearSolver& K_factor);

}  // namespace contactqp::detail
