// The dense LCP solver of lcp.hpp: primal-dual active-set steps, projected Newton as the
// safeguard against cycling.
#include <Eigen/Cholesky>  // LDLT for the nearly singular case
#include <algorithm>
#include <cmath>
#include <set>

#include "lcp.hpp"
#include "qp/norms.hpp"

// LAPACK's Cholesky (OpenBLAS on Debian): S_AA of a thousand rows takes ~0.1 s with Eigen's
// portable kernels and a few times less with OpenBLAS's, once per active-set step.
extern "C" {
void dpotrf_(const char* uplo, const int* n, double* A, const int* lda, int* info);
void dpotrs_(const char* uplo, const int* n, const int* nrhs, const double* A, const int* lda, double* B,
             const int* ldb, int* info);
}

namespace contactqp::detail {
namespace {

VectorXd gather(const VectorXd& v, const std::vector<int>& index) {
  VectorXd out(index.size());
  for (size_t k = 0; k < index.size(); ++k) out[k] = v[index[k]];
  return out;
}

// ‖min(λ, w)‖∞ relative to the sizes of λ, h and w: zero exactly at a solution.
double natural_residual(const VectorXd& lambda, const VectorXd& w, const VectorXd& h) {
  const double scale = std::max({inf_norm(lambda), inf_norm(h), inf_norm(w)});
  const double r = lambda.size() ? inf_norm(lambda.cwiseMin(w)) : 0.0;
  return scale > 0 ? r / scale : r;
}

// q(λ) = ½λᵀSλ − hᵀλ, written with w = Sλ − h so that it needs no product.
double merit(const VectorXd& lambda, const VectorXd& w, const VectorXd& h) { return 0.5 * lambda.dot(w - h); }

// Armijo constant and the most halvings of the projected Newton step: 2⁻⁶⁰ is below round-off.
constexpr double kArmijo = 1e-4;
constexpr int kMaxHalvings = 60;

}  // namespace

VectorXd DenseLcpOperator::times(const VectorXd& x) const { return S_ * x; }

bool solve_dense_spd(MatrixXd block, const VectorXd& b, VectorXd& x) {
  const int n = static_cast<int>(block.rows()), one = 1;
  int info = 0;
  MatrixXd factor = block;
  if (n > 0) dpotrf_("L", &n, factor.data(), &n, &info);
  if (info == 0) {
    x = b;
    if (n > 0) dpotrs_("L", &n, &one, factor.data(), &n, x.data(), &n, &info);
    return info == 0 && x.allFinite();
  }
  // Not numerically positive definite (S singular or nearly so): the pivoted LDLᵀ leaves the
  // components of zero pivots at zero, a solution of the consistent part.
  block.triangularView<Eigen::StrictlyUpper>() = block.transpose();
  Eigen::LDLT<MatrixXd> ldlt(block);
  if (ldlt.info() != Eigen::Success) return false;
  x = ldlt.solve(b);
  return x.allFinite();
}

bool DenseLcpOperator::solve_principal(const std::vector<int>& A, const VectorXd& b, VectorXd& x) const {
  const Eigen::Index a = static_cast<Eigen::Index>(A.size());
  MatrixXd block(a, a);
  for (Eigen::Index j = 0; j < a; ++j)
    for (Eigen::Index i = j; i < a; ++i) block(i, j) = S_(A[i], A[j]);  // LLT reads the lower triangle
  return solve_dense_spd(std::move(block), b, x);
}

VectorXd MatrixFreeLcpOperator::times(const VectorXd& x) const {
  ++products_;
  return product_(x);
}

bool MatrixFreeLcpOperator::solve_principal(const std::vector<int>& A, const VectorXd& b, VectorXd& x) const {
  const Eigen::Index a = static_cast<Eigen::Index>(A.size());
  auto apply = [&](const VectorXd& p) {
    VectorXd full = VectorXd::Zero(m_);
    for (Eigen::Index k = 0; k < a; ++k) full[A[k]] = p[k];
    return gather(times(full), A);
  };
  if (x.size() != a || !x.allFinite()) x = VectorXd::Zero(a);
  const double b_norm = b.norm();
  if (b_norm == 0) {
    x.setZero();
    return true;
  }
  VectorXd r = b - apply(x);
  VectorXd p = r;
  double rr = r.squaredNorm();
  // CG on S_AA, symmetric positive definite; in exact arithmetic it ends within |A| steps.
  for (Eigen::Index k = 0; k < 2 * a + 10 && std::sqrt(rr) > cg_tol_ * b_norm; ++k) {
    const VectorXd Sp = apply(p);
    const double curvature = p.dot(Sp);
    if (!(curvature > 0)) return false;
    const double alpha = rr / curvature;
    x += alpha * p;
    r -= alpha * Sp;
    const double rr_next = r.squaredNorm();
    p = r + (rr_next / rr) * p;
    rr = rr_next;
  }
  return x.allFinite();
}

LcpResult solve_lcp(const LcpOperator& S, const VectorXd& h, const LcpOptions& options) {
  const int m = S.size();
  auto residual_of = [&](const VectorXd& lambda, const VectorXd& w) {
    return options.residual ? options.residual(lambda, w) : natural_residual(lambda, w, h);
  };
  VectorXd diagonal(m);
  for (int i = 0; i < m; ++i) diagonal[i] = S.diagonal(i);

  LcpResult result;
  // (lambda, w): the current iterate, w = Sλ − h always. Active-set steps may leave λ_i < 0
  // on their active set; the stopping test and the safeguard use the projection max(λ, 0).
  VectorXd lambda = options.start.size() == m ? VectorXd(options.start.cwiseMax(0.0)) : VectorXd::Zero(m);
  VectorXd w = lambda.isZero(0) ? VectorXd(-h) : VectorXd(S.times(lambda) - h);
  // The feasible point with the least q seen so far: where the safeguard starts.
  VectorXd best_lambda = lambda, best_w = w;
  double best_q = merit(lambda, w, h);

  auto accept = [&](const VectorXd& feasible_lambda, const VectorXd& feasible_w) {
    result.lambda = feasible_lambda;
    result.w = feasible_w;
    result.residual = residual_of(feasible_lambda, feasible_w);
    if (options.on_iterate && result.iterations > 0) options.on_iterate(result.iterations, feasible_lambda);
    const double q = merit(feasible_lambda, feasible_w, h);
    if (q < best_q) {
      best_q = q;
      best_lambda = feasible_lambda;
      best_w = feasible_w;
    }
    return result.residual <= options.tol;
  };

  std::set<std::vector<int>> seen;  // active sets of the active-set steps so far
  bool newton = false;
  double epsilon = 0;  // projected Newton's bound tolerance, fixed when the safeguard starts
  if (accept(lambda, w)) {
    result.outcome = LcpOutcome::Converged;
  } else {
    while (result.iterations < options.max_iterations) {
      if (!newton) {
        std::vector<int> active;
        for (int i = 0; i < m; ++i)
          if (lambda[i] - w[i] / diagonal[i] > 0) active.push_back(i);
        VectorXd lambda_active = gather(lambda, active).cwiseMax(0.0);
        bool solved = false;
        if (seen.insert(active).second) {
          solved = S.solve_principal(active, gather(h, active), lambda_active);
        } else {
          result.cycle_detected = true;
          if (!options.safeguard) {
            result.outcome = LcpOutcome::Cycled;
            break;
          }
        }
        if (!solved) {
          if (!options.safeguard) {
            result.outcome = LcpOutcome::Stalled;
            break;
          }
          // A repeated active set (a cycle) or a singular S_AA: continue monotonically.
          newton = true;
          lambda = best_lambda;
          w = best_w;
          const VectorXd scaled_h = h.cwiseQuotient(diagonal);
          epsilon = 1e-2 * std::max(inf_norm(lambda), inf_norm(scaled_h));
          if (!(epsilon > 0)) epsilon = 1.0;
          continue;
        }
        lambda.setZero();
        for (size_t k = 0; k < active.size(); ++k) lambda[active[k]] = lambda_active[k];
        w = S.times(lambda) - h;
        ++result.iterations;
        ++result.active_set_steps;
        const bool feasible = (lambda.array() >= 0).all();
        const VectorXd projected = lambda.cwiseMax(0.0);
        if (feasible ? accept(lambda, w) : accept(projected, S.times(projected) - h)) {
          result.outcome = LcpOutcome::Converged;
          break;
        }
      } else {
        // Bertsekas' projected Newton step on q over λ ≥ 0, from a feasible λ: bounds that are
        // nearly active with the gradient w pushing outwards move along −w/S_ii; the others
        // take the Newton step of their block; then an Armijo search along the projection arc.
        double stationarity = 0;
        for (int i = 0; i < m; ++i)
          stationarity = std::max(stationarity, std::abs(lambda[i] - std::max(0.0, lambda[i] - w[i] / diagonal[i])));
        const double bound_tol = std::min(epsilon, stationarity);
        std::vector<int> free;
        VectorXd d = VectorXd::Zero(m);
        for (int i = 0; i < m; ++i) {
          if (lambda[i] <= bound_tol && w[i] > 0)
            d[i] = -w[i] / diagonal[i];
          else
            free.push_back(i);
        }
        VectorXd d_free = VectorXd::Zero(static_cast<Eigen::Index>(free.size()));
        if (S.solve_principal(free, gather(w, free), d_free)) {
          for (size_t k = 0; k < free.size(); ++k) d[free[k]] = -d_free[k];
        } else {
          for (int i : free) d[i] = -w[i] / diagonal[i];
        }
        std::vector<char> is_free(m, 0);
        for (int i : free) is_free[i] = 1;
        const double q = merit(lambda, w, h);
        double alpha = 1;
        bool decreased = false;
        VectorXd trial, trial_w;
        for (int halving = 0; halving <= kMaxHalvings; ++halving, alpha *= 0.5) {
          trial = (lambda + alpha * d).cwiseMax(0.0);
          trial_w = S.times(trial) - h;
          double expected = 0;
          for (int i = 0; i < m; ++i) expected += is_free[i] ? -alpha * w[i] * d[i] : w[i] * (lambda[i] - trial[i]);
          if (q - merit(trial, trial_w, h) >= kArmijo * expected && expected >= 0) {
            decreased = true;
            break;
          }
        }
        if (!decreased) {
          result.outcome = LcpOutcome::Stalled;
          break;
        }
        lambda = trial;
        w = trial_w;
        ++result.iterations;
        ++result.newton_steps;
        if (accept(lambda, w)) {
          result.outcome = LcpOutcome::Converged;
          break;
        }
      }
    }
  }
  result.active = static_cast<int>((result.lambda.array() > 0).count());
  return result;
}

}  // namespace contactqp::detail
