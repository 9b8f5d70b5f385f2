// What the two Uzawa backends (uzawa.cpp, uzawa_accelerated.cpp) share: the choice of the
// step ρ from the spectrum of S = B K⁻¹ Bᵀ, the stopping rule, the divergence guard, the
// fallback of --rho auto, and the closing message. Each backend supplies only its loop.
//
// Which rows the spectrum covers (docs/rho.md): the working set R of the rows that
// the unconstrained solution u₀ = K⁻¹f violates, (B u₀ − g)_i > 0. These are exactly the rows
// Uzawa's first step activates from λ = 0, and on contact problems they contain the rows that
// end up active, so λ_max(S_R) bounds the active block's λ_max, which sets the asymptotic rate,
// while staying close to what the first iterates see. When no row is violated, R is every row.
//
// With friction the loops run on the multipliers y = (λ_N, λ_T) of multiplier_set.hpp: the rows
// C = [B; T], the projection onto λ_N ≥ 0 and the discs, S = C K⁻¹ Cᵀ; R adds every tangential
// row (a sticking node's λ_T moves freely inside its disc, so its rows belong to the block that
// sets the rate). The stopping rule's primal violation is that of the normal rows.
#pragma once

#include <limits>
#include <map>
#include <string>
#include <vector>

#include "backends.hpp"
#include "multiplier_set.hpp"
#include "spectrum.hpp"

namespace contactqp::detail {

enum class UzawaVariant { Plain, Accelerated };

// The step and where it came from, in the backend's (scaled) units.
struct UzawaStep {
  double rho = 0;                                            // the step used
  double rho_max = std::numeric_limits<double>::infinity();  // 2/λ_max(S_R)
  double rho_opt = std::numeric_limits<double>::infinity();  // 2/(λ_min(S_R) + λ_max(S_R))
  bool all_rows = true;                                      // R is every row (else the working set)
  SpectrumEstimate spectrum;
  // Iterations without progress that count as not converging (DivergenceGuard): 200 at the
  // automatic step or above, more in proportion below it (see choose_step).
  double stall_window = 200;
};

// The stopping rule of both variants: the projected step λ_next − λ_from, relative to λ_next
// (∞-norm), and the primal violation max(0, Bu − g) (the first m entries of r = C u − c),
// relative to the displacement (the length scale of certificate.hpp). Converged when the
// larger of the two is ≤ tol.
double uzawa_residual(const MultiplierSet& set, const VectorXd& u, const VectorXd& r, const VectorXd& lambda_from,
                      const VectorXd& lambda_next);

// Watches an iteration and says when to stop. Three signs that it will not converge:
//  - it expands: the step ‖λ_next − λ_from‖₂ or the relative residual grows a millionfold
//    over the smallest seen;
//  - a row alternates between contact and separation on every one of the last
//    kFlipWindow iterations, with a positive value that is not negligible, and the residual
//    has not improved meanwhile: the 2-cycle λ_i = 0 ↔ ρ r_i that the projection makes of an
//    expanding component. It may involve a few rows only while the others still converge and
//    shrink the step, which the next sign would miss;
//  - no progress for `stall_window` iterations (UzawaStep), progress being a new smallest
//    relative residual or a new smallest step. Plain Uzawa's map is nonexpansive for
//    ρ < 2/λ_max(S), so its step never grows and shrinks every iteration however small ρ is,
//    even while the relative residual lingers at a plateau (a primal violation the slowly
//    growing λ has not removed). The accelerated iteration's step and residual do rise for a
//    while when the contact set changes, for a number of iterations that grows like 1/ρ.
class DivergenceGuard {
 public:
  enum class Verdict { Continue, Converged, Diverged };
  // n_rows: the normal rows (the first entries of λ), whose switching on and off is watched.
  DivergenceGuard(double tol, int n_rows, double stall_window)
      : tol_(tol), stall_window_(stall_window), flips_(n_rows, 0) {}
  Verdict check(int k, double residual, const VectorXd& lambda_from, const VectorXd& lambda_next);
  double best() const { return best_residual_; }
  double last() const { return last_residual_; }

 private:
  double tol_;
  double stall_window_;
  std::vector<int> flips_;  // per row: consecutive iterations that switched it on or off
  double best_residual_ = std::numeric_limits<double>::infinity();
  double best_step_ = std::numeric_limits<double>::infinity();
  double last_residual_ = std::numeric_limits<double>::infinity();
  int last_residual_progress_ = 0;  // last iteration with a new smallest residual
  int last_step_progress_ = 0;      // last iteration with a new smallest step
};

// Everything one run of a loop needs: the multipliers' rows and set, and the start y₀ with
// u_start = u(y₀), already solved (y₀ = 0 and u_start = K⁻¹f, or the warm start).
struct UzawaContext {
  const QuadraticProgram& qp;
  const LinearSolver& K_factor;
  const SolveOptions& options;
  const MultiplierSet& set;
  const VectorXd& lambda_start;
  const VectorXd& u_start;
};

// What a loop returns: its outcome and the last finite iterate, u = u(λ) (λ = y with friction).
struct UzawaRun {
  Status status = Status::MaxIterations;
  VectorXd u, lambda;
  int iterations = 0;
  double residual = std::numeric_limits<double>::infinity();       // at the last iterate
  double best_residual = std::numeric_limits<double>::infinity();  // the smallest seen
  std::map<std::string, double> diagnostics;                       // the variant's own counts
};

// The bookkeeping of every iteration of a loop: the stopping rule on the step λ_from → λ_next
// taken at u = u(λ_from), the observer, the divergence guard, and the iterate to return.
class IterationMonitor {
 public:
  IterationMonitor(const UzawaContext& context, const UzawaStep& step, int first_k, UzawaRun& run);
  // True when the loop must stop (converged or diverged); run.status says which. Otherwise
  // (u, λ_from) becomes the iterate returned if the next one is not finite.
  bool stop(int k, const VectorXd& u, const VectorXd& r, const VectorXd& lambda_from, const VectorXd& lambda_next);
  // Fills run.iterations and the residuals after the loop ended at iteration k.
  void finish(int k);

 private:
  const UzawaContext& context_;
  int first_k_;
  UzawaRun& run_;
  DivergenceGuard guard_;
};

// One run from the context's start with a fixed step; `first_k` numbers the iterates for the
// observer (k = first_k + 1, ...) so that a restarted run continues the count.
using UzawaLoop = UzawaRun (*)(const UzawaContext& context, const UzawaStep& step, int first_k, int max_iterations);

// The whole backend around a loop: factor K, choose ρ, run, fall back (with --rho auto) to
// the step from every row when the working-set step does not converge, fill the result.
// `radii`: the discs' radii when qp has friction (Tresca's thresholds, or Coulomb's μλ_N frozen
// by the fixed point); ignored without friction.
SolveResult run_uzawa(const QuadraticProgram& qp, const VectorXd& radii, const SolveOptions& options,
                      UzawaVariant variant, UzawaLoop loop);

// The backend entry of both variants: run_uzawa on the frictionless or Tresca problem,
// Coulomb's fixed point around it (coulomb_fixed_point.hpp).
SolveResult solve_uzawa_variant(const QuadraticProgram& qp, const SolveOptions& options, UzawaVariant variant,
                                UzawaLoop loop);

// Both variants take no backend options (their step is --rho): InputError on a key addressed to them.
void check_uzawa_options(const SolveOptions& options);

}  // namespace contactqp::detail
