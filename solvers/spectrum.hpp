// Spectrum estimates of the condensed contact operator S = B K⁻¹ Bᵀ (m × m, symmetric
// positive semidefinite), applied matrix-free: S v = B (K⁻¹ (Bᵀ v)), one solve with the
// CHOLMOD factor of K per application.
#pragma once

#include "contactqp/cholesky.hpp"
#include "contactqp/qp.hpp"

namespace contactqp::detail {

struct SpectrumEstimate {
  double lambda_max = 0;  // estimate of the largest eigenvalue of S (0 when m = 0)
  int applications = 0;   // products with S, i.e. solves with K, spent on the estimate
  double seconds = 0;
};

// Power iteration with the Rayleigh quotient, stopped when it changes by less than
// `rel_tol` between steps or after `max_steps` products. The Rayleigh quotient approaches
// λ_max from below.
SpectrumEstimate estimate_lambda_max(const QuadraticProgram& qp, const CholeskyFactor& K_factor,
                                     double rel_tol = 1e-4, int max_steps = 200);

}  // namespace contactqp::detail
