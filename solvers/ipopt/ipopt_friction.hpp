// The ipopt backend's NLPs (internal: only solvers/ipopt*.cpp include Ipopt's headers).
//
// Without friction Ipopt solves the primal QP (ipopt.cpp). With friction it solves the dual of
// Tresca's problem in saddle form, one smooth form for both dimensions:
//
//   minimise  ½ uᵀKu + gᵀλ_N + offsetᵀλ_T
//   subject to  K u + Bᵀλ_N + Tᵀλ_T = f      (n linear equalities)
//               λ_N ≥ 0
//               2D: −r_i ≤ λ_T,i ≤ r_i        (bounds: the problem is a QP)
//               3D: ‖λ_T,i‖²/r_i ≤ r_i       (one convex quadratic inequality per node with r_i > 0)
//               λ_T,i = 0 where r_i = 0       (fixed variables)
//
// At u = K⁻¹(f − Bᵀλ_N − Tᵀλ_T) the objective is −θ(λ_N, λ_T) (certificate.hpp), so its minimum
// is Tresca's dual optimum, and u, the variable, is the primal answer. Why not the primal: the
// friction term Σ r_i ‖T_i u − offset_i‖ is not differentiable where a node sticks, and the
// usual smooth forms (w_i ≥ ‖z_i‖ as w_i² ≥ ‖z_i‖²) lose their constraint qualification exactly
// there (z = 0, w = 0), while the disc ‖λ_T,i‖ ≤ r_i is smooth and its constraint's gradient
// 2λ_T,i/r_i vanishes only inside the disc, where the constraint is inactive. Everything stays
// sparse: the Hessian is K plus a diagonal, the Jacobian [K Bᵀ Tᵀ] plus 2λ_T/r. Dividing the
// quadratic constraint by r_i gives it force units like the others.
#pragma once

#include <IpTNLP.hpp>

#include "contactqp/qp.hpp"

namespace contactqp::detail {

// Beyond Ipopt's nlp_lower_bound_inf / nlp_upper_bound_inf (±1e19 by default): no bound.
inline constexpr double kNoBound = 1e300;

// What solve_ipopt reads back from either NLP.
class ContactNlp : public Ipopt::TNLP {
 public:
  VectorXd u, lambda, lambda_t;  // the solution Ipopt reported last
  bool has_solution = false;
  bool diverged = false;   // the primal iterate grew beyond any stiffness (ipopt.cpp)
  int n_inequalities = 0;  // Ipopt's inequality constraints: sizes compl_inf_tol
  virtual void disable_observer() {}
};

// Writes the pattern (values == null) or the values (times `factor`) of a sparse matrix into
// Ipopt's triplet arrays; returns the number of entries written.
Ipopt::Index copy_entries(const SparseMatrix& A, Ipopt::Index* rows, Ipopt::Index* cols, Ipopt::Number* values,
                          double factor);

// The dual NLP above for qp's friction with the discs' radii `radii`.
Ipopt::SmartPtr<ContactNlp> make_friction_dual_nlp(const QuadraticProgram& qp, const VectorXd& radii);

}  // namespace contactqp::detail
