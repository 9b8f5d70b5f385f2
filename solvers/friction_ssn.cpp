#include "friction_ssn.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "lcp.hpp"
#include "qp/friction_sets.hpp"

namespace contactqp::detail {
namespace {

// A free direction of the Newton system: e = c₀ e_{j₀} (+ c₁ e_{j₁}) in y's space, and the γ
// added to its diagonal.
struct Direction {
  int j[2] = {-1, -1};
  double c[2] = {0, 0};
  double gamma = 0;
};

// What a Newton step needs at one iterate: the fixed part of y, the free directions, and the
// state of each node (for the cycle test and the counts).
struct Linearisation {
  VectorXd y_fixed;
  std::vector<Direction> free;
  std::vector<signed char> state;  // per component group: see state_of
  int gap = 0, stick = 0, slip = 0;
};

class Ssn {
 public:
  Ssn(const FrictionSsnProblem& problem, const FrictionSsnOptions& options)
      : p_(problem), options_(options), M_(static_cast<int>(problem.h.size())) {
    d_.resize(M_);
    for (int j = 0; j < M_; ++j) d_[j] = problem.S(j, j) > 0 ? problem.S(j, j) : 1.0;
    // One d per tangential block, so that the projection onto the disc stays isotropic.
    const int nd = p_.n_directions;
    fixed_slip_.assign(p_.m, false);
    zero_row_.assign(M_, false);
    for (int j = p_.m; j < M_; ++j) zero_row_[j] = problem.S(j, j) == 0;
    for (int i = 0; i < p_.m; ++i) {
      const int base = p_.m + i * nd;
      const double d = d_.segment(base, nd).maxCoeff();
      d_.segment(base, nd).setConstant(d);
      // A node whose tangential rows are zero (its tangential DOFs prescribed): its slip does not
      // depend on y, so its λ_T is the natural map's limit, fixed.
      fixed_slip_[i] = problem.S.diagonal().segment(base, nd).cwiseAbs().maxCoeff() == 0;
    }
  }

  FrictionSsnResult run();

 private:
  VectorXd project(const VectorXd& y) const { return project_multipliers(y, p_.m, p_.n_directions, p_.radii); }
  VectorXd gradient(const VectorXd& y) const { return p_.S * y - p_.h; }
  Linearisation linearise(const VectorXd& y, const VectorXd& w) const;
  bool newton_point(const Linearisation& lin, VectorXd& y_next) const;
  // Records a feasible point; true when it meets the tolerance.
  bool accept(const VectorXd& y, const VectorXd& w);
  // q(y) = ½yᵀSy − hᵀy from y and its w = Sy − h.
  double objective(const VectorXd& y, const VectorXd& w) const { return 0.5 * y.dot(w - p_.h); }
  void gradient_steps(int count, VectorXd& y, VectorXd& w);
  // A Newton point's step from the feasible y, projected and halved until q decreases (or, at
  // full length, the residual does): true, with y and w moved, when one is found.
  bool newton_search(const VectorXd& y_newton, VectorXd& y, VectorXd& w);
  // When the Newton point from y's states finds no descent: the states of that (unprojected)
  // point, then of the next, as plain primal-dual active-set steps, each point tried by
  // newton_search from y. True, with y and w moved, when one descends.
  bool newton_chain(VectorXd y_newton, VectorXd& y, VectorXd& w);

  const FrictionSsnProblem& p_;
  const FrictionSsnOptions& options_;
  int M_;
  VectorXd d_;
  std::vector<bool> fixed_slip_;  // per node: zero tangential rows
  std::vector<bool> zero_row_;    // per row of y: a tangential row of T that is zero
  FrictionSsnResult result_;
  VectorXd best_y_, best_w_;
};

Linearisation Ssn::linearise(const VectorXd& y, const VectorXd& w) const {
  const int m = p_.m, nd = p_.n_directions;
  Linearisation lin;
  lin.y_fixed = VectorXd::Zero(M_);
  lin.state.assign(2 * m, 0);
  for (int i = 0; i < m; ++i) {
    const bool contact = y[i] - w[i] / d_[i] > 0;
    if (contact) {
      Direction e;
      e.j[0] = i;
      e.c[0] = 1;
      lin.free.push_back(e);
    }
    lin.state[i] = contact ? 1 : 0;
    const int base = m + i * nd;
    const double r = p_.radii[i];
    double v[2] = {0, 0}, norm2 = 0;
    for (int k = 0; k < nd; ++k) {
      v[k] = y[base + k] - w[base + k] / d_[base];
      norm2 += v[k] * v[k];
    }
    const double norm = std::sqrt(norm2);
    if (fixed_slip_[i]) {
      // λ_T = r slip/‖slip‖ for the fixed slip = −w_T (0 without slip): the limit d → 0 of proj(v).
      double slip2 = 0;
      for (int k = 0; k < nd; ++k) slip2 += w[base + k] * w[base + k];
      lin.state[m + i] = 0;
      if (r > 0 && slip2 > 0)
        for (int k = 0; k < nd; ++k) lin.y_fixed[base + k] = -r * w[base + k] / std::sqrt(slip2);
    } else if (!(r > 0)) {
      lin.state[m + i] = 0;  // λ_T = 0
    } else if (norm <= r) {
      lin.state[m + i] = 1;  // stick: every direction free, no slip
      for (int k = 0; k < nd; ++k) {
        // A zero row of T (one prescribed tangential DOF, on a symmetry plane) moves nothing:
        // its λ_T component stays 0, and the system stays positive definite.
        if (zero_row_[base + k]) continue;
        Direction e;
        e.j[0] = base + k;
        e.c[0] = 1;
        lin.free.push_back(e);
      }
    } else {
      // Slip: λ_T = r n along n = v/‖v‖; in 3D the direction t ⊥ n stays free with γ.
      lin.state[m + i] = static_cast<signed char>(nd == 1 ? (v[0] > 0 ? 2 : 3) : 2);
      for (int k = 0; k < nd; ++k) lin.y_fixed[base + k] = r * v[k] / norm;
      if (nd == 2) {
        Direction e;
        e.j[0] = base;
        e.c[0] = -v[1] / norm;
        e.j[1] = base + 1;
        e.c[1] = v[0] / norm;
        e.gamma = d_[base] * (norm - r) / r;
        lin.free.push_back(e);
      }
    }
    if (!contact)
      ++lin.gap;
    else if (lin.state[m + i] == 1)
      ++lin.stick;
    else
      ++lin.slip;
  }
  return lin;
}

bool Ssn::newton_point(const Linearisation& lin, VectorXd& y_next) const {
  const int F = static_cast<int>(lin.free.size());
  const VectorXd rhs_full = p_.h - p_.S * lin.y_fixed;
  MatrixXd A(F, F);
  VectorXd rhs(F);
  for (int a = 0; a < F; ++a) {
    const Direction& ea = lin.free[a];
    rhs[a] = 0;
    for (int s = 0; s < 2 && ea.j[s] >= 0; ++s) rhs[a] += ea.c[s] * rhs_full[ea.j[s]];
    for (int b = a; b < F; ++b) {  // the lower triangle, which solve_dense_spd reads
      const Direction& eb = lin.free[b];
      double entry = 0;
      for (int s = 0; s < 2 && ea.j[s] >= 0; ++s)
        for (int t = 0; t < 2 && eb.j[t] >= 0; ++t) entry += ea.c[s] * eb.c[t] * p_.S(ea.j[s], eb.j[t]);
      A(b, a) = entry;
    }
    A(a, a) += ea.gamma;
  }
  VectorXd x(F);
  if (!solve_dense_spd(std::move(A), rhs, x)) return false;
  y_next = lin.y_fixed;
  for (int a = 0; a < F; ++a)
    for (int s = 0; s < 2 && lin.free[a].j[s] >= 0; ++s) y_next[lin.free[a].j[s]] += lin.free[a].c[s] * x[a];
  return y_next.allFinite();
}

bool Ssn::accept(const VectorXd& y, const VectorXd& w) {
  const double residual = options_.residual(y, w);
  // The best point is the one with the least residual; the gradient steps start from it.
  if (best_y_.size() == 0 || residual < result_.residual) {
    result_.residual = residual;
    best_y_ = y;
    best_w_ = w;
  }
  return residual <= options_.tol;
}

// Projected gradient steps from y: direction d = proj(y − αw) − y, the exact minimiser of the
// quadratic q along it (within the segment, which the convex set contains), then the
// Barzilai–Borwein length α = dᵀd / dᵀSd for the next step. Monotone in q.
void Ssn::gradient_steps(int count, VectorXd& y, VectorXd& w) {
  double alpha = 1.0 / d_.maxCoeff();
  for (int k = 0; k < count && result_.iterations < options_.max_iterations; ++k) {
    const VectorXd d = project(y - alpha * w) - y;
    const VectorXd Sd = p_.S * d;
    const double curvature = d.dot(Sd), slope = w.dot(d);
    if (!(curvature > 0) || !(slope < 0)) break;  // stationary to round-off
    const double t = std::min(1.0, -slope / curvature);
    y += t * d;
    w += t * Sd;
    ++result_.iterations;
    ++result_.gradient_steps;
    if (accept(y, w)) return;
    alpha = d.squaredNorm() / curvature;
  }
}

bool Ssn::newton_search(const VectorXd& y_newton, VectorXd& y, VectorXd& w) {
  const double q = objective(y, w);
  const double residual = options_.residual(y, w);
  // q's round-off near the answer: below it a decrease is not measurable.
  const double noise = 1e-13 * std::max(std::abs(q), std::abs(0.5 * y.dot(w + p_.h)));
  const VectorXd step = y_newton - y;
  for (double t = 1; t >= 1.0 / 1024; t *= 0.5) {
    const VectorXd trial = project(y + t * step);
    const VectorXd trial_w = gradient(trial);
    const double q_trial = objective(trial, trial_w);
    // Armijo's sufficient decrease along the projected arc (w is q's gradient); within q's
    // round-off, a full step that lowers the residual.
    const bool decrease = q_trial <= q + 1e-4 * w.dot(trial - y) && q_trial < q - noise;
    const bool refines = t == 1 && q_trial <= q + noise && options_.residual(trial, trial_w) < residual;
    if (decrease || refines) {
      y = trial;
      w = trial_w;
      return true;
    }
  }
  return false;
}

bool Ssn::newton_chain(VectorXd y_newton, VectorXd& y, VectorXd& w) {
  // Near the answer a few nodes sit on the edge between stick and slip (|v| ≈ r), and the states
  // that y predicts can make a face whose point lies uphill (scenes/mindlin-spheres.json's finer
  // meshes: 600–1000 gradient steps per load step before). The unprojected Newton point's own
  // states are the active-set step the method would take next; following them a few points
  // reaches a face that descends (2–3 points there), and the search keeps the iterates monotone,
  // so the states still cannot cycle.
  constexpr int kChain = 4;
  for (int k = 0; k < kChain && result_.iterations < options_.max_iterations; ++k) {
    const Linearisation lin = linearise(y_newton, gradient(y_newton));
    VectorXd next;
    if (!newton_point(lin, next)) return false;
    ++result_.iterations;  // each point costs a Newton step's factorisation
    ++result_.newton_steps;
    if (newton_search(next, y, w)) return true;
    y_newton = std::move(next);
  }
  return false;
}

FrictionSsnResult Ssn::run() {
  result_.residual = std::numeric_limits<double>::infinity();
  VectorXd y = options_.start.size() == M_ ? project(options_.start) : VectorXd(VectorXd::Zero(M_));
  VectorXd w = gradient(y);
  if (accept(y, w)) {
    result_.outcome = SsnOutcome::Converged;
  } else {
    // Newton from the feasible y, its step projected and damped until q decreases (so that the
    // states cannot cycle); when Newton finds no descent, projected gradient steps from y, then
    // Newton again. Both keep y feasible.
    constexpr int kGradientSteps = 50;  // gradient steps before Newton resumes
    constexpr int kMaxStalls = 3;       // gradient rounds in a row that neither lower q nor the residual
    int stalls = 0;
    while (result_.iterations < options_.max_iterations) {
      const Linearisation lin = linearise(y, w);
      VectorXd y_next;
      if (newton_point(lin, y_next) && (newton_search(y_next, y, w) || newton_chain(y_next, y, w))) {
        ++result_.iterations;
        ++result_.newton_steps;
        if (accept(y, w)) {
          result_.outcome = SsnOutcome::Converged;
          break;
        }
        stalls = 0;
        continue;
      }
      const double q_before = objective(y, w), best_before = result_.residual;
      gradient_steps(kGradientSteps, y, w);
      if (result_.residual <= options_.tol) {
        result_.outcome = SsnOutcome::Converged;
        break;
      }
      if (objective(y, w) < q_before || result_.residual < best_before)
        stalls = 0;
      else if (++stalls >= kMaxStalls) {
        result_.outcome = SsnOutcome::Stalled;
        break;
      }
    }
  }
  result_.y = best_y_;
  result_.w = best_w_;
  const Linearisation final_state = linearise(result_.y, result_.w);
  result_.gap = final_state.gap;
  result_.stick = final_state.stick;
  result_.slip = final_state.slip;
  return result_;
}

}  // namespace

FrictionSsnResult solve_friction_ssn(const FrictionSsnProblem& problem, const FrictionSsnOptions& options) {
  return Ssn(problem, options).run();
}

}  // namespace contactqp::detail
