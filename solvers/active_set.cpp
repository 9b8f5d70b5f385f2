// The active-set backend: the contact problem condensed onto its candidate rows, solved as
// a small LCP, then one solve for u.
//
//   factorize   P K Pᵀ = L Lᵀ                                    (once, CHOLMOD)
//   condense    S = B K⁻¹ Bᵀ = WᵀW,  h = B K⁻¹ f − g,  W = L⁻¹ P Bᵀ on its elimination-tree paths
//   iterate     λ ≥ 0, w = Sλ − h ≥ 0, λᵀw = 0                    (lcp.hpp: active set + safeguard)
//   recover     u = K⁻¹ (f − Bᵀλ)                                  (one solve)
//
// w = g − Bu is the remaining gap of each row (docs/architecture.md: B u − g = h − Sλ ≤ 0).
#include <algorithm>
#include <cmath>
#include <memory>

#include "active_set_friction.hpp"
#include "backend_options.hpp"
#include "backends.hpp"
#include "contactqp/backends/active_set.hpp"
#include "contactqp/certificate.hpp"
#include "contactqp/errors.hpp"
#include "lcp.hpp"
#include "multiplier_set.hpp"
#include "qp/friction_sets.hpp"

namespace contactqp::detail {
namespace {

// Bytes a dense S and one Cholesky factor of its active block take: 2 × 8 m².
double dense_bytes(int m) { return 16.0 * m * m; }

// The backend options it reads (keys unaddressed or addressed "active_set.key").
ActiveSetOptions effective_options(const SolveOptions& options) {
  ActiveSetOptions settings = options.get<ActiveSetOptions>();
  for (const auto& [key, value] : options_for(Backend::ActiveSet, options.backend_options)) {
    if (key == "max_dense_mb") {
      const double mb = parse_number(value, option_field(key));
      require(mb > 0, option_field(key), value, "must be a positive number of MiB");
      settings.max_dense_bytes = mb * 1024.0 * 1024.0;
    } else {
      throw InputError(option_field(key), "= \"" + value + "\": not an option of active_set; valid: max_dense_mb");
    }
  }
  return settings;
}

// The stopping rule in the certificate's terms (certificate.hpp), from λ ≥ 0 and w = g − Bu:
// primal violation ‖max(0, −w)‖∞ / L and complementarity max|λ_i w_i| / (max(‖λ‖∞, F) L), for
// a length scale L and a force scale F.
double relative_residual(const VectorXd& lambda, const VectorXd& w, double L, double F) {
  if (lambda.size() == 0) return 0;
  const double violation = std::max(0.0, -w.minCoeff());
  const double complementarity = lambda.cwiseProduct(w).cwiseAbs().maxCoeff();
  const double force = std::max(inf_norm(lambda), F);
  const double primal = L > 0 ? violation / L : violation;
  const double product = force * L;
  return std::max(primal, product > 0 ? complementarity / product : complementarity);
}

// The rule while iterating, without u: L = ‖Bu‖∞ = ‖g − w‖∞ and F = max(‖f‖∞, ‖Bᵀλ‖∞) are
// lower bounds of certify()'s length and force scales (which also take ‖u‖∞ and ‖Ku‖∞,
// unknown until u is recovered), so the test is at least as strict as certify()'s residuals.
// Stationarity holds by construction of u.
double lower_bound_residual(const QuadraticProgram& qp, const VectorXd& lambda, const VectorXd& w) {
  if (lambda.size() == 0) return 0;
  return relative_residual(lambda, w, inf_norm(qp.g - w),
                           std::max(inf_norm(qp.f), inf_norm(qp.B.transpose() * lambda)));
}

void check_active_set_options(const SolveOptions& options) { effective_options(options); }

// The frictionless problem (or one whose friction exerts no force): condense B, solve the LCP.
SolveResult solve_condensed_lcp(const QuadraticProgram& qp, const SolveOptions& options,
                                const ActiveSetOptions& settings) {
  const VectorXd warm = initial_multipliers(qp, options, MultiplierSet(qp, VectorXd()));
  SolveResult result;
  const int m = qp.n_constraints();

  result.K_factor = factor_of_K(qp, options, result.timings, result.message);
  if (!result.K_factor) return result;
  const LinearSolver& K_factor = *result.K_factor;

  // Condense. Dense S when it fits, else S v = B K⁻¹ Bᵀ v matrix-free.
  Stopwatch clock;
  const bool dense = dense_bytes(m) <= settings.max_dense_bytes;
  Condensation condensed;
  VectorXd h;
  std::unique_ptr<LcpOperator> S;
  MatrixFreeLcpOperator* matrix_free = nullptr;
  if (dense) {
    condensed = K_factor.condense(qp.B, qp.f);
    h = condensed.c - qp.g;
    S = std::make_unique<DenseLcpOperator>(condensed.S);
    result.diagnostics["condensed_columns"] = static_cast<double>(condensed.reached_columns);
    result.diagnostics["condensed_entries"] = static_cast<double>(condensed.entries);
    result.diagnostics["condensed_peak_entries"] = static_cast<double>(condensed.peak_entries);
  } else {
    h = qp.B * K_factor.solve(qp.f) - qp.g;
    // The inner CG must resolve S_AA λ_A = h_A well below the outer tolerance, or the
    // active-set decisions and the stopping test see its error.
    auto product = [&qp, &K_factor](const VectorXd& v) -> VectorXd {
      return qp.B * K_factor.solve(VectorXd(qp.B.transpose() * v));
    };
    auto owned = std::make_unique<MatrixFreeLcpOperator>(m, product, std::min(1e-12, 1e-3 * options.tol));
    matrix_free = owned.get();
    S = std::move(owned);
  }
  result.diagnostics["dense"] = dense ? 1 : 0;
  const double condense_seconds = clock.seconds();
  result.timings.add("condense", condense_seconds);

  // Iterate on the LCP.
  clock.restart();
  LcpOptions lcp;
  lcp.tol = options.tol;
  lcp.max_iterations = options.max_iterations;
  lcp.start = warm;  // the last load step's λ, when given: its active set is the first guess
  lcp.residual = [&qp](const VectorXd& lambda, const VectorXd& w) { return lower_bound_residual(qp, lambda, w); };
  if (options.observer) {
    // Only for convergence studies: each iterate's u costs one solve more.
    lcp.on_iterate = [&](int k, const VectorXd& lambda) {
      options.observer(k, K_factor.solve(VectorXd(qp.f - qp.B.transpose() * lambda)), lambda);
    };
  }
  const LcpResult lcp_result = solve_lcp(*S, h, lcp);
  const double iterate_seconds = clock.seconds();
  result.timings.add("iterate", iterate_seconds);

  // Recover u with one solve.
  clock.restart();
  result.lambda = lcp_result.lambda;
  result.u = K_factor.solve(VectorXd(qp.f - qp.B.transpose() * result.lambda));
  const double recover_seconds = clock.seconds();
  result.timings.add("recover", recover_seconds);
  result.timings.add("solve", condense_seconds + iterate_seconds + recover_seconds);

  result.iterations = lcp_result.iterations;
  result.diagnostics["active_set_steps"] = lcp_result.active_set_steps;
  result.diagnostics["newton_steps"] = lcp_result.newton_steps;
  result.diagnostics["cycle_detected"] = lcp_result.cycle_detected ? 1 : 0;
  result.diagnostics["active_constraints"] = lcp_result.active;
  result.diagnostics["lcp_residual"] = lcp_result.residual;
  if (matrix_free) result.diagnostics["S_products"] = static_cast<double>(matrix_free->products());

  // The lower bound of L can be round-off where it should not matter: a block pressed flat
  // on a plane at its own level closes every row exactly, so Bu = g = 0 and ‖Bu‖∞ ~ 1e-17,
  // and the iteration "stalled at residual 1" on the exact answer. Where the iteration did
  // not stop on its own test, measure the recovered (u, λ) with certify()'s scales instead.
  LcpOutcome outcome = lcp_result.outcome;
  double residual = lcp_result.residual;
  bool measured_with_u = false;
  if (outcome == LcpOutcome::Stalled || outcome == LcpOutcome::MaxIterations) {
    const double measured = relative_residual(result.lambda, VectorXd(qp.g - qp.B * result.u),
                                              length_scale(qp, result.u), force_scale(qp, result.u, result.lambda));
    if (measured <= options.tol) {
      outcome = LcpOutcome::Converged;
      residual = measured;
      measured_with_u = true;
      result.diagnostics["lcp_residual"] = measured;
    }
  }

  std::string how = std::to_string(m) + " candidate rows, " + std::to_string(lcp_result.active) + " in contact";
  if (!dense)
    how += "; S applied matrix-free: a dense S would need " + short_number(dense_bytes(m) / 1048576.0) +
           " MiB, over the limit of " + short_number(settings.max_dense_bytes / 1048576.0) + " MiB";
  if (lcp_result.cycle_detected) how += "; the active-set steps cycled and projected Newton finished";
  if (measured_with_u) how += "; residual measured with the recovered u, as the iteration's bound ‖Bu‖∞ was round-off";
  if (!K_factor.ok()) {
    result.status = Status::NumericalError;
    result.message = "a solve with K failed (" + how + "): " + K_factor.message();
    return result;
  }
  switch (outcome) {
    case LcpOutcome::Converged:
      result.status = Status::Converged;
      result.message = "converged: condensed LCP residual " + short_number(residual) +
                       " <= " + short_number(options.tol) + " (" + how + ")";
      break;
    case LcpOutcome::MaxIterations:
      result.status = Status::MaxIterations;
      result.message = "stopped after " + std::to_string(options.max_iterations) + " iterations with residual " +
                       short_number(lcp_result.residual) + " (" + how + "); more iterations may help";
      break;
    case LcpOutcome::Cycled:  // only without the safeguard, which this backend always uses
      result.status = Status::Diverged;
      result.message = "the active-set steps cycled (" + how + ")";
      break;
    case LcpOutcome::Stalled:
      result.status = Status::NumericalError;
      result.message = "the projected Newton line search stalled at residual " + short_number(lcp_result.residual) +
                       " (" + how + "): round-off in S; a larger tol may help";
      break;
  }
  return result;
}

SolveResult solve_active_set(const QuadraticProgram& qp, const SolveOptions& options) {
  const ActiveSetOptions settings = effective_options(options);
  if (!without_friction_force(qp.friction)) return solve_active_set_friction(qp, options, settings);
  SolveResult result = solve_condensed_lcp(qp, options, settings);
  if (!qp.friction.empty()) result.lambda_t = VectorXd::Zero(qp.friction.T.rows());
  return result;
}

}  // namespace
}  // namespace contactqp::detail

CONTACTQP_BUILTIN(active_set) {
  BackendRegistration active_set;
  active_set.name = "active_set";
  active_set.summary = "primal-dual active set (semismooth Newton) on the contact-condensed problem";
  active_set.order = 50;
  active_set.option_names = {"max_dense_mb"};
  active_set.check_options = check_active_set_options;
  active_set.solve = solve_active_set;
  active_set.problem_kinds = {ProblemKind::Frictionless, ProblemKind::Tresca, ProblemKind::Coulomb};
  register_backend(active_set);
}
