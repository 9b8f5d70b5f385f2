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
#pragma once

#include <limits>
#include <string>

#include "contactqp/qp.hpp"

namespace contactqp {

struct Certificate {
  double stationarity = 0;        // relative, see above
  double primal_feasibility = 0;  // relative
  double dual_feasibility = 0;    // relative
  double complementarity = 0;     // relative
  double objective = 0;           // J(u), in the QP's energy units
  double dual_objective = 0;      // θ(λ); −inf is reported as not finite (K singular and f − Bᵀλ ∉ range K)
  double duality_gap = 0;         // J(u) − θ(λ), energy units; ≥ 0 up to round-off when u is feasible
  double relative_gap = 0;        // duality_gap / energy scale
  bool dual_available = true;     // false when K could not be factorised; θ and the gaps are then 0

  double kkt_max() const;  // the largest of the four relative KKT residuals
};

// K_factor: a solver of qp.K to reuse (e.g. SolveResult::K_factor), of any kind: θ needs one
// solve with the stationarity residual r, and an iterative solver's relative inner tolerance
// (docs/linear-solvers.md) keeps the correction ½ rᵀK⁻¹r accurate as r → 0. When null,
// certify() factorises K itself (one sparse Cholesky).
Certificate certify(const QuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda,
                    const LinearSolver* K_factor = nullptr);

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

// The scales above, exposed so that backends' stopping rules measure the same things.
double force_scale(const QuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda);
double force_scale(const VectorXd& f, const VectorXd& Ku, const VectorXd& Btl);  // from the products
double length_scale(const QuadraticProgram& qp, const VectorXd& u);

}  // namespace contactqp
