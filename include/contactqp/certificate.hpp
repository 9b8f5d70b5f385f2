// The optimality certificate: the same numbers for every backend, computed from (qp, u, λ)
// alone, outside the backends.
//
// KKT conditions of  min ½uᵀKu − fᵀu  s.t.  Bu ≤ g  (Lagrangian L = J + λᵀ(Bu − g)):
//   stationarity         K u − f + Bᵀλ = 0
//   primal feasibility   B u − g ≤ 0
//   dual feasibility     λ ≥ 0
//   complementarity      λ_i (Bu − g)_i = 0
// Each residual is made relative (dimensionless) by a scale of its own units:
//   force scale   F = max(‖f‖∞, ‖Ku‖∞, ‖Bᵀλ‖∞)
//   length scale  L = max(‖u‖∞, ‖Bu‖∞)            (rows of B have unit norm)
//   stationarity        = ‖Ku − f + Bᵀλ‖∞ / F
//   primal_feasibility  = ‖max(0, Bu − g)‖∞ / L
//   dual_feasibility    = ‖max(0, −λ)‖∞ / max(‖λ‖∞, F)
//   complementarity     = max_i |λ_i (Bu − g)_i| / (max(‖λ‖∞, F·tiny) · L)
// A zero scale (u = 0, f = 0, ...) makes the residual absolute. The duality gap J(u) − θ(λ)
// is made relative by the energy scale max(|J|, |θ|, ½uᵀKu, |fᵀu|).
//
// The dual function θ(λ) = −½(f − Bᵀλ)ᵀK⁻¹(f − Bᵀλ) − gᵀλ needs one solve with K; it is
// evaluated as θ = L(u, λ) − ½ rᵀK⁻¹r with r the stationarity residual, which is exact and
// keeps full precision near the optimum where r is tiny.
//
// With friction (friction.hpp), from (u, λ, λ_T), slip = T u − offset and the radii r_i of the
// discs λ_T,i must lie in (threshold_i under Tresca, μ_i max(0, λ_N,i) under Coulomb):
//   force scale   F = max(‖f‖∞, ‖Ku‖∞, ‖Bᵀλ‖∞, ‖Tᵀλ_T‖∞)
//   length scale  L = max(‖u‖∞, ‖Bu‖∞, ‖slip‖∞)
//   stationarity  = ‖Ku − f + Bᵀλ + Tᵀλ_T‖∞ / F
//   tangential    = max_i ‖λ_T,i − proj_{D_i}(λ_T,i + ρ slip_i)‖₂ / F,   ρ = F/L
//                   (the natural map of the tangential condition: zero exactly when every node
//                   sticks with ‖λ_T,i‖ ≤ r_i and slip_i = 0, or slips with λ_T,i = r_i
//                   slip_i/‖slip_i‖; ρ = F/L weighs a slip of L like a force of F, so the
//                   residual is dimensionless and the same in any units; ρ = 1 when L or F is 0)
//   the other three as above, on the normal rows.
// J(u) = ½uᵀKu − fᵀu + Σ r_i ‖slip_i‖ (Tresca's primal objective) and
// θ = −½ rᵀK⁻¹r − gᵀλ − offsetᵀλ_T with r = f − Bᵀλ − Tᵀλ_T, evaluated as above from the
// Lagrangian L = J₀ + λᵀ(Bu − g) + λ_Tᵀ slip; the energy scale adds Σ r_i ‖slip_i‖. The gap is
// ≥ 0 when u is feasible and every λ_T,i lies in its disc, and zero exactly at the optimum. Under
// Coulomb's law the radii come from the λ being certified: J and θ are those of the Tresca
// problem with threshold μλ_N, which a Coulomb solution solves, so its gap is zero too.
#pragma once

#include <limits>
#include <string>

#include "contactqp/certificate_values.hpp"
#include "contactqp/qp.hpp"

namespace contactqp {

// K_factor: a solver of qp.K to reuse (e.g. SolveResult::K_factor), of any kind: θ needs one
// solve with the stationarity residual r, and an iterative solver's relative inner tolerance
// (docs/linear-solvers.md) keeps the correction ½ rᵀK⁻¹r accurate as r → 0. When null,
// certify() factorises K itself (one sparse Cholesky).
Certificate certify(const QuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda,
                    const LinearSolver* K_factor = nullptr);
// With friction: λ_T = lambda_t (m · n_directions entries; empty reads as 0).
Certificate certify(const QuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda, const VectorXd& lambda_t,
                    const LinearSolver* K_factor = nullptr);

// The status a solve may claim, given the certificate of its answer: `proposed` (the backend's
// own) when it claims no more than the certificate shows, Inaccurate when the backend claims
// Converged but the relative KKT residual (kkt_max) or, where θ is available, the relative
// duality gap |J − θ|/energy exceeds kCertifiedFactor · tol. The factor allows for round-off
// between a backend's stopping test (in its scaled copy) and the certificate (in the caller's
// units), not for a looser tolerance: docs/extremes.md, "What converged means".
inline constexpr double kCertifiedFactor = 10.0;
bool meets_tolerance(const Certificate& certificate, double tol);
Status certified_status(const Certificate& certificate, double tol, Status proposed);
// Stores the certificate in the result and holds its status to it (certified_status), saying in
// the message what the certificate showed when it overrules the backend.
void apply_certificate(SolveResult& result, const Certificate& certificate, double tol);

// What the certificate's formulas read of (qp, u, λ): maxima and sums over the entries. A caller
// that holds u, λ and the rows of K, f, B and g in pieces (one per process of a distributed
// problem) takes each maximum and sum over the pieces, and gets from certificate_from() the
// certificate certify() gives for the whole: one implementation of the formulas for both.
struct CertificateTerms {
  double f_max = 0, Ku_max = 0, Btl_max = 0;  // ‖f‖∞, ‖Ku‖∞, ‖Bᵀλ‖∞
  double u_max = 0, Bu_max = 0;               // ‖u‖∞, ‖Bu‖∞
  double stationarity_max = 0;                // ‖Ku − f + Bᵀλ‖∞
  double violation_max = 0;                   // max(0, max_i (Bu − g)_i)
  double negative_max = 0;                    // max(0, −min_i λ_i)
  double lambda_max = 0;                      // ‖λ‖∞
  double complementarity_max = 0;             // max_i |λ_i (Bu − g)_i|
  double uKu = 0, fu = 0, lambda_slack = 0;   // uᵀKu, fᵀu, λᵀ(Bu − g)
  // rᵀK⁻¹r for the stationarity residual r (one solve with K); NaN when no solver of K is at
  // hand or it failed: θ and the gap are then not available.
  double r_K_inverse_r = std::numeric_limits<double>::quiet_NaN();
};
CertificateTerms certificate_terms(const QuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda);
// The same with K u given: for a problem whose K this process holds only a share of (its
// library sums the shares' products over the processes).
CertificateTerms certificate_terms(const QuadraticProgram& qp, const VectorXd& Ku, const VectorXd& u,
                                   const VectorXd& lambda);
Certificate certificate_from(const CertificateTerms& terms);
// certify() with K u given, friction included: for a problem whose K this process holds only a
// share of (its library sums the shares' products over the processes; every other vector whole).
// θ needs K_factor, a solver of the whole K; without one the dual is not available.
Certificate certify_given_Ku(const QuadraticProgram& qp, const VectorXd& Ku, const VectorXd& u, const VectorXd& lambda,
                             const VectorXd& lambda_t, const LinearSolver* K_factor);

// The scales above, exposed so that backends' stopping rules measure the same things.
double force_scale(const QuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda,
                   const VectorXd& lambda_t = VectorXd());
double force_scale(const VectorXd& f, const VectorXd& Ku, const VectorXd& Btl);  // from the products
double length_scale(const QuadraticProgram& qp, const VectorXd& u);

}  // namespace contactqp
