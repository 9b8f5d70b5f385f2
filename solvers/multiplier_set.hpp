// The multipliers of the contact problem as one vector y and the set they live in, so that a
// dual method is written once for the frictionless and the frictional problem.
//
// Without friction y = λ (m entries, λ ≥ 0) on the rows C = B, c = g. With friction (friction.hpp)
// y = (λ_N, λ_T) on the stacked rows C = [B; T], c = [g; offset] (m + m·n_directions entries):
// λ_N ≥ 0, and each λ_T,i in the disc of radius r_i (an interval in 2D). Then
//   u(y) = K⁻¹(f − Cᵀy),   C u(y) − c = (B u − g, slip),
// the dual function is θ(y) = −½ (f − Cᵀy)ᵀK⁻¹(f − Cᵀy) − cᵀy with gradient C u(y) − c, and a
// projected gradient step is y ← proj(y + ρ (C u − c)): Uzawa's step on both kinds of rows.
// Under Coulomb's law the radii are frozen by the caller (coulomb_fixed_point.hpp). When every
// radius is 0 the set is the frictionless one (y = λ on the rows of B) and λ_T = 0: the same
// numbers as the problem without friction.
#pragma once

#include "contactqp/qp.hpp"

namespace contactqp::detail {

class MultiplierSet {
 public:
  // `radii`: the discs' radii (m entries) when qp has friction; ignored without. With
  // `always_stacked` the rows are [B; T] whenever qp has friction, even if every radius is 0
  // (active_set condenses them once for all of Coulomb's fixed-point steps).
  MultiplierSet(const QuadraticProgram& qp, const VectorXd& radii, bool always_stacked = false);

  bool frictional() const { return n_directions_ > 0; }     // y holds λ_T (some radius is positive)
  int normal_rows() const { return m_; }                    // m: the first rows of y are λ_N
  int rows() const { return static_cast<int>(c_.size()); }  // all rows of y
  int n_directions() const { return n_directions_; }
  const VectorXd& radii() const { return radii_; }
  const SparseMatrix& C() const { return *C_; }  // B, or [B; T]
  const VectorXd& c() const { return *c_ptr_; }  // g, or [g; offset]

  // The projection of y onto the set: max(0, ·) on λ_N, the disc on each λ_T,i.
  VectorXd project(const VectorXd& y) const;
  // The parts of y.
  VectorXd lambda(const VectorXd& y) const { return y.head(m_); }
  // λ_T: m · n_directions entries when the QP has friction (zeros when every radius is 0), else none.
  VectorXd lambda_t(const VectorXd& y) const {
    return frictional() ? VectorXd(y.tail(y.size() - m_)) : VectorXd(VectorXd::Zero(tangential_rows_));
  }
  // y from (λ, λ_T), either of which may be empty (zeros); projected onto the set.
  VectorXd join(const VectorXd& lambda, const VectorXd& lambda_t) const;

 private:
  int m_ = 0;
  int n_directions_ = 0;
  int tangential_rows_ = 0;  // rows of T, whether or not y holds them
  VectorXd radii_;
  SparseMatrix stacked_;  // [B; T] with friction; empty without
  VectorXd c_;            // [g; offset] with friction; g without (a copy: small)
  const SparseMatrix* C_ = nullptr;
  const VectorXd* c_ptr_ = nullptr;
};

// The warm start of options.initial as y (sizes checked: InputError naming the field), or an
// empty vector when the options carry no multipliers.
VectorXd initial_multipliers(const QuadraticProgram& qp, const SolveOptions& options, const MultiplierSet& set);

}  // namespace contactqp::detail
