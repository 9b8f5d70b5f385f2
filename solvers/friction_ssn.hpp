// The condensed Tresca problem and its semismooth Newton method (the active_set backend with
// friction, docs/backends.md). With C = [B; T], S = C K⁻¹ Cᵀ and h = C K⁻¹ f − [g; offset] the
// dual of Tresca's problem is
//
//   minimise q(y) = ½ yᵀSy − hᵀy   over  y = (λ_N, λ_T):  λ_N ≥ 0,  ‖λ_T,i‖ ≤ r_i,
//
// and w = Sy − h holds the gaps g − Bu (normal rows) and minus the slips (tangential rows).
// Its optimality condition is the fixed point y = proj(y − D⁻¹w) (D > 0 diagonal, constant on
// each node's tangential block). Per node the projection has a state, and a semismooth Newton
// step on that equation (Hüeber, Stadler & Wohlmuth 2008; Alart & Curnier 1991; Hintermüller,
// Ito & Kunisch 2002) solves one linear system on the free components:
//   gap    (λ_N − w/d ≤ 0):        λ_N = 0
//   contact(λ_N − w/d > 0):        w_N = 0                       (the gap closes)
//   stick  (‖v‖ ≤ r, v = λ_T − w_T/d): w_T = 0                    (no slip)
//   slip   (‖v‖ > r):              n·λ_T = r along n = v/‖v‖, and in 3D along the other
//                                  direction t: t·w_T + γ t·λ_T = 0 with γ = d (‖v‖ − r)/r ≥ 0
// (the linearised projection v ↦ r v/‖v‖); rows with r = 0 keep λ_T = 0. The system matrix is
// EᵀSE + diag(γ) on the free directions E: symmetric positive definite, one dense Cholesky.
// In 2D the slip state fixes λ_T = ±r, and the method is the primal-dual active-set method for
// the box. The iterates stay feasible: Newton's point is projected and its step halved until q
// decreases (a full step that lowers the residual counts too), so the states cannot cycle (plain
// primal-dual active-set steps do, on the 94 slipping nodes of scenes/sliding-block.json). Where
// the Newton point finds no descent, the states of that point (then of the next, up to four:
// plain active-set steps) give further Newton points, each tried by the same search; where none
// descends, projected gradient steps with Barzilai–Borwein lengths and an exact line search
// (monotone, globally convergent) move y, then Newton again.
#pragma once

#include <Eigen/Core>
#include <functional>

namespace contactqp::detail {

using Eigen::MatrixXd;
using Eigen::VectorXd;

struct FrictionSsnProblem {
  const MatrixXd& S;      // M × M, M = m (1 + n_directions); symmetric positive (semi)definite
  const VectorXd& h;      // M
  int m = 0;              // normal rows, first in y
  int n_directions = 1;   // 1 (2D: an interval) or 2 (3D: a disc)
  const VectorXd& radii;  // m: r_i ≥ 0
};

struct FrictionSsnOptions {
  double tol = 1e-10;
  int max_iterations = 100;  // Newton and gradient steps together
  // The relative residual of a feasible y and its w = Sy − h (the backend's stopping rule).
  std::function<double(const VectorXd& y, const VectorXd& w)> residual;
  VectorXd start;  // initial y (projected); empty: 0
};

enum class SsnOutcome { Converged, MaxIterations, Stalled };

struct FrictionSsnResult {
  SsnOutcome outcome = SsnOutcome::MaxIterations;
  VectorXd y, w;  // the best feasible iterate and its w = Sy − h
  double residual = 0;
  int iterations = 0;
  int newton_steps = 0;
  int gradient_steps = 0;
  int gap = 0, stick = 0, slip = 0;  // nodes per state at the end (a node in contact sticks or slips)
};

FrictionSsnResult solve_friction_ssn(const FrictionSsnProblem& problem, const FrictionSsnOptions& options);

}  // namespace contactqp::detail
