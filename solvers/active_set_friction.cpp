#include "active_set_friction.hpp"

#include <algorithm>
#include <cmath>

#include "backends.hpp"
#include "contactqp/certificate.hpp"
#include "contactqp/number_format.hpp"
#include "coulomb_fixed_point.hpp"
#include "friction_ssn.hpp"
#include "multiplier_set.hpp"
#include "qp/friction_sets.hpp"
#include "qp/norms.hpp"

namespace contactqp::detail {
namespace {

// The certificate's relative residuals (certificate.hpp) of y = (λ_N, λ_T) with w = Sy − h,
// without u: stationarity holds by construction of u = K⁻¹(f − Cᵀy), so ‖Ku‖∞ = ‖f − Cᵀy‖∞
// and F is exact. certify()'s L = max(‖u‖∞, ‖Bu‖∞, ‖slip‖∞) needs u; here L = max(‖Ku‖∞ / ‖K‖∞,
// ‖g − w_N‖∞, ‖w_T‖∞), with ‖Ku‖∞ ≤ ‖K‖∞ ‖u‖∞ and g − w_N = Bu, is a lower bound, which makes
// every residual an upper bound of certify()'s (the natural map's residual grows with ρ = F/L).
// The rows alone are not enough: a zone whose rows all close and stick (one node pushed onto
// the plane it started on: Bu = 0, slip = 0) has them of round-off, and ρ = F/L then turns
// round-off slips into residuals of 0.03 that no Newton step lowers. The bound from K stays
// within a factor 5–10 of ‖u‖∞ on the shipped frictional scenes.
double condensed_residual(const QuadraticProgram& qp, const MultiplierSet& set, const VectorXd& radii,
                          const VectorXd& y, const VectorXd& w, double K_norm) {
  // `set`: the stacked rows (y's layout); `radii`: the discs of this Tresca solve; K_norm: ‖K‖∞.
  const int m = set.normal_rows();
  const VectorXd lambda = set.lambda(y), lambda_t = set.lambda_t(y);
  const VectorXd gap = w.head(m), slip = -w.tail(w.size() - m);
  const double Ku = inf_norm(VectorXd(qp.f - set.C().transpose() * y));
  const double F = std::max({inf_norm(qp.f), Ku, inf_norm(VectorXd(qp.B.transpose() * lambda)),
                             inf_norm(VectorXd(qp.friction.T.transpose() * lambda_t))});
  const double L = std::max({K_norm > 0 ? Ku / K_norm : 0.0, inf_norm(VectorXd(qp.g - gap)), inf_norm(slip)});
  const double violation = m ? std::max(0.0, -gap.minCoeff()) : 0.0;
  const double complementarity = m ? lambda.cwiseProduct(gap).cwiseAbs().maxCoeff() : 0.0;
  const double rho = F > 0 && L > 0 ? F / L : 1.0;
  return std::max({relative(violation, L), relative(complementarity, std::max(inf_norm(lambda), F) * L),
                   relative(natural_map_residual(qp.friction, lambda_t, radii, slip, rho), F)});
}

// ‖K‖∞: the largest sum of a row's absolute values.
double infinity_norm(const SparseMatrix& K) {
  VectorXd sums = VectorXd::Zero(K.rows());
  for (int k = 0; k < K.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(K, k); it; ++it) sums[it.row()] += std::abs(it.value());
  return sums.size() ? sums.maxCoeff() : 0.0;
}

const char* name_of(SsnOutcome outcome) {
  switch (outcome) {
    case SsnOutcome::Converged:
      return "converged";
    case SsnOutcome::MaxIterations:
      return "stopped at the iteration limit";
    case SsnOutcome::Stalled:
      return "stalled";
  }
  return "unknown";
}

}  // namespace

SolveResult solve_active_set_friction(const QuadraticProgram& qp, const SolveOptions& options,
                                      const ActiveSetOptions& settings) {
  // The rows [B; T] and y's layout, whatever the radii of each Tresca solve.
  const MultiplierSet stacked(qp, qp.friction.threshold, true);
  initial_multipliers(qp, options, stacked);  // checks the warm start's sizes before any work
  const int M = stacked.rows(), m = stacked.normal_rows();
  SolveResult result;
  const double bytes = 16.0 * M * M;
  if (bytes > settings.max_dense_bytes) {
    result.u = VectorXd::Zero(qp.n_dofs());
    result.lambda = VectorXd::Zero(m);
    result.lambda_t = VectorXd::Zero(M - m);
    result.message = "active_set with friction needs the condensed operator dense: " + std::to_string(M) +
                     " stacked rows need " + short_number(bytes / 1048576.0) + " MiB, over the limit of " +
                     short_number(settings.max_dense_bytes / 1048576.0) +
                     " MiB; raise it (--backend-option max_dense_mb=...) or use uzawa_accel";
    return result;
  }
  result.K_factor = factor_of_K(qp, options, result.timings, result.message);
  if (!result.K_factor) return result;
  const LinearSolver& K_factor = *result.K_factor;

  Stopwatch clock;
  const Condensation condensed = K_factor.condense(stacked.C(), qp.f);
  const VectorXd h = condensed.c - stacked.c();
  result.timings.add("condense", clock.seconds());
  result.diagnostics["condensed_columns"] = static_cast<double>(condensed.reached_columns);
  result.diagnostics["condensed_entries"] = static_cast<double>(condensed.entries);

  const double K_norm = infinity_norm(qp.K);
  // One Tresca solve on the condensed problem with the radii given; u is not recovered here.
  FrictionSsnResult last;
  int newton = 0, gradient = 0;
  auto tresca = [&](const VectorXd& radii, const SolveOptions& step_options) {
    const MultiplierSet& set = stacked;
    FrictionSsnOptions ssn;
    ssn.tol = step_options.tol;
    ssn.max_iterations = step_options.max_iterations;
    ssn.residual = [&](const VectorXd& y, const VectorXd& w) {
      return condensed_residual(qp, set, radii, y, w, K_norm);
    };
    // The warm start, as given (the method projects it onto this solve's discs).
    VectorXd start;
    if (step_options.initial.lambda.size() || step_options.initial.lambda_t.size()) {
      start = VectorXd::Zero(M);
      if (step_options.initial.lambda.size()) start.head(m) = step_options.initial.lambda;
      if (step_options.initial.lambda_t.size()) start.tail(M - m) = step_options.initial.lambda_t;
    }
    ssn.start = start;
    Stopwatch step_clock;
    last = solve_friction_ssn({condensed.S, h, m, qp.friction.n_directions, radii}, ssn);
    newton += last.newton_steps;
    gradient += last.gradient_steps;
    SolveResult step;
    step.timings.add("iterate", step_clock.seconds());
    step.status = last.outcome == SsnOutcome::Converged       ? Status::Converged
                  : last.outcome == SsnOutcome::MaxIterations ? Status::MaxIterations
                                                              : Status::NumericalError;
    step.iterations = last.iterations;
    step.lambda = set.lambda(last.y);
    step.lambda_t = set.lambda_t(last.y);
    step.message = std::string(name_of(last.outcome)) + ": condensed residual " + short_number(last.residual) +
                   " after " + std::to_string(last.newton_steps) + " Newton and " +
                   std::to_string(last.gradient_steps) + " gradient steps";
    return step;
  };
  SolveResult solved = qp.friction.law == FrictionLaw::Coulomb ? solve_coulomb_by_fixed_point(qp, options, tresca)
                                                               : tresca(qp.friction.threshold, options);

  clock.restart();
  VectorXd y(M);
  y << solved.lambda, solved.lambda_t;
  result.u = K_factor.solve(VectorXd(qp.f - stacked.C().transpose() * y));
  result.timings.add("recover", clock.seconds());
  result.timings.merge(solved.timings);
  result.timings.add("solve",
                     result.timings.get("condense") + result.timings.get("iterate") + result.timings.get("recover"));
  result.lambda = std::move(solved.lambda);
  result.lambda_t = std::move(solved.lambda_t);
  result.iterations = solved.iterations;
  result.status = solved.status;
  for (const auto& [name, value] : solved.diagnostics) result.diagnostics[name] = value;
  result.diagnostics["newton_steps"] = newton;
  result.diagnostics["gradient_steps"] = gradient;
  result.diagnostics["gap_nodes"] = last.gap;
  result.diagnostics["stick_nodes"] = last.stick;
  result.diagnostics["slip_nodes"] = last.slip;
  result.diagnostics["condensed_residual"] = last.residual;

  // As without friction (active_set.cpp): the iteration's lower bound of L can be round-off;
  // where it did not meet its own test, measure with certify()'s scales and the recovered u.
  if (result.status != Status::Converged && K_factor.ok()) {
    const Certificate c = certify(qp, result.u, result.lambda, result.lambda_t, &K_factor);
    if (c.kkt_max() <= options.tol) {
      result.status = Status::Converged;
      solved.message += "; residual measured with the recovered u: " + short_number(c.kkt_max());
    }
  }
  const std::string how = std::to_string(m) + " candidate rows with " + std::to_string(qp.friction.n_directions) +
                          " tangential directions each; " + std::to_string(last.gap) + " gap, " +
                          std::to_string(last.stick) + " stick, " + std::to_string(last.slip) + " slip";
  if (!K_factor.ok()) {
    result.status = Status::NumericalError;
    result.message = "a solve with K failed (" + how + "): " + K_factor.message();
  } else {
    result.message = solved.message + " (" + how + ")";
  }
  return result;
}

}  // namespace contactqp::detail
