// Coulomb's law as the fixed point of Tresca problems (Haslinger 1983; Dostál et al.; Siconos'
// fc3d_TrescaFixedPoint): Coulomb's disc radius μ_i λ_N,i depends on the unknown λ_N, Tresca's
// is given, so
//
//   s⁰ = μ λ_N⁰                    λ_N⁰ from the warm start (options.initial), or 0: the first
//                                   solve is then the frictionless problem (λ_T = 0)
//   (u, λ_N, λ_T)ᵏ⁺¹ = Tresca(sᵏ)   warm-started from step k, with the same solver of K
//   sᵏ⁺¹ = μ λ_N,ᵏ⁺¹               stop when ‖sᵏ⁺¹ − sᵏ‖∞ ≤ tol ‖sᵏ⁺¹‖∞
//
// The map s ↦ μ λ_N(s) is a contraction for small enough μ (the uniqueness range of the
// discrete Coulomb problem); for large μ it may cycle, which the step limit reports.
#pragma once

#include <functional>

#include "contactqp/qp.hpp"

namespace contactqp::detail {

// One Tresca solve of the backend with the discs' radii `radii` (m) in place of the QP's
// thresholds, from options.initial and with options.K_factor when set.
using TrescaSolve = std::function<SolveResult(const VectorXd& radii, const SolveOptions& options)>;

// The most Tresca solves of one Coulomb problem.
constexpr int kMaxFixedPointSteps = 200;

// The fixed point above around `tresca`. The result is the last Tresca solve's, with the
// iterations of all of them, their timings summed, and the diagnostics "fixed_point_steps" (the
// number of Tresca solves) and "fixed_point_change" (the last relative change of s).
SolveResult solve_coulomb_by_fixed_point(const QuadraticProgram& qp, const SolveOptions& options,
                                         const TrescaSolve& tresca);

}  // namespace contactqp::detail
