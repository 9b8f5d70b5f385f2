// The linear complementarity problem of the contact-condensed dual (docs/backends.md, "active_set"):
//
//   λ ≥ 0,   w = Sλ − h ≥ 0,   λᵀw = 0          S symmetric positive definite (m × m)
//
// equivalently  min q(λ) = ½λᵀSλ − hᵀλ  over λ ≥ 0. For the contact QP, S = B K⁻¹ Bᵀ,
// h = B K⁻¹ f − g, λ are the contact forces and w = g − Bu the remaining gaps.
//
// Solved by the primal-dual active-set method (Hintermüller, Ito & Kunisch 2002: a semismooth
// Newton method for min(λ, w/diag S) = 0): with A = {i : λ_i − w_i/S_ii > 0}, set λ_I = 0 and
// solve S_AA λ_A = h_A, then recompute A. The next iterate depends on A alone, so an active
// set seen before means the method cycles (it can for S that is not an M-matrix); the solver
// then continues with Bertsekas' projected Newton method (1982) from the best point seen,
// which decreases q monotonically and ends in finitely many steps on a strictly convex QP.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

namespace contactqp::detail {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// S through what the active-set method needs: products, and solves with principal blocks.
class LcpOperator {
 public:
  virtual ~LcpOperator() = default;
  virtual int size() const = 0;
  virtual VectorXd times(const VectorXd& x) const = 0;  // S x
  virtual double diagonal(int i) const = 0;             // S_ii, or a positive stand-in
  // x = S_AA⁻¹ b for the sorted index set A (b and x of size |A|; x holds a starting guess on
  // entry for iterative variants). False when S_AA is numerically singular.
  virtual bool solve_principal(const std::vector<int>& A, const VectorXd& b, VectorXd& x) const = 0;
};

// x = A⁻¹ b for a symmetric positive (semi)definite A of which only the lower triangle is read:
// LAPACK's Cholesky, or a pivoted LDLᵀ when A is not numerically positive definite. False when
// neither gives a finite x.
bool solve_dense_spd(MatrixXd A, const VectorXd& b, VectorXd& x);

// S stored dense; S_AA by a dense Cholesky factorisation (LDLᵀ when S_AA is nearly singular).
class DenseLcpOperator : public LcpOperator {
 public:
  explicit DenseLcpOperator(const MatrixXd& S) : S_(S) {}
  int size() const override { return static_cast<int>(S_.rows()); }
  VectorXd times(const VectorXd& x) const override;
  double diagonal(int i) const override { return S_(i, i) > 0 ? S_(i, i) : 1.0; }
  bool solve_principal(const std::vector<int>& A, const VectorXd& b, VectorXd& x) const override;

 private:
  const MatrixXd& S_;
};

// S applied matrix-free (e.g. one solve with K per product); S_AA by conjugate gradients,
// stopped at relative residual `cg_tol`. For candidate sets too large for a dense S.
class MatrixFreeLcpOperator : public LcpOperator {
 public:
  MatrixFreeLcpOperator(int m, std::function<VectorXd(const VectorXd&)> product, double cg_tol)
      : m_(m), product_(std::move(product)), cg_tol_(cg_tol) {}
  int size() const override { return m_; }
  VectorXd times(const VectorXd& x) const override;
  double diagonal(int) const override { return 1.0; }
  bool solve_principal(const std::vector<int>& A, const VectorXd& b, VectorXd& x) const override;
  long long products() const { return products_; }  // products with S so far

 private:
  int m_;
  std::function<VectorXd(const VectorXd&)> product_;
  double cg_tol_;
  mutable long long products_ = 0;
};

struct LcpOptions {
  double tol = 1e-10;        // stop when residual(λ, w) ≤ tol
  int max_iterations = 100;  // active-set and projected Newton steps together
  // The relative residual of a feasible iterate (λ ≥ 0, w = Sλ − h). Empty: the natural
  // residual ‖min(λ, w)‖∞ relative to max(‖λ‖∞, ‖h‖∞, ‖w‖∞).
  std::function<double(const VectorXd& lambda, const VectorXd& w)> residual;
  bool safeguard = true;  // false: plain active-set steps only (to show that they can cycle)
  VectorXd start;         // initial λ (≥ 0); empty: λ = 0
  // Called with each feasible iterate (k = 1, 2, ...); for convergence studies.
  std::function<void(int k, const VectorXd& lambda)> on_iterate;
};

enum class LcpOutcome {
  Converged,      // residual ≤ tol
  MaxIterations,  // iteration limit reached
  Cycled,         // plain active-set steps repeated an active set (only with safeguard = false)
  Stalled,        // the safeguard's line search could not decrease q: round-off level reached
};

struct LcpResult {
  LcpOutcome outcome = LcpOutcome::MaxIterations;
  VectorXd lambda, w;   // the best iterate: λ ≥ 0, w = Sλ − h
  double residual = 0;  // residual(λ, w)
  int iterations = 0;   // active-set plus projected Newton steps (one solve with S_AA each)
  int active_set_steps = 0;
  int newton_steps = 0;  // safeguard steps
  bool cycle_detected = false;
  int active = 0;  // rows with λ_i > 0 at the end
};

LcpResult solve_lcp(const LcpOperator& S, const VectorXd& h, const LcpOptions& options);

}  // namespace contactqp::detail
