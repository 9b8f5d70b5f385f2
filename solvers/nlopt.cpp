// The NLopt backend: the dual problem
//
//   maximise θ(λ) = −½ (f − Bᵀλ)ᵀ K⁻¹ (f − Bᵀλ) − gᵀλ   subject to λ ≥ 0,
//
// handed to a bound-constrained, gradient-based NLopt method as the minimisation of −θ, with
// ∇θ(λ) = B u(λ) − g and u(λ) = K⁻¹(f − Bᵀλ): one solve with the CHOLMOD factor of K per
// evaluation. u is recovered from the final λ.
//
// Stopping rule (ours, not NLopt's): the certificate's relative residuals at (u(λ), λ) are all
// below tol. Stationarity and dual feasibility hold by construction (u solves K u = f − Bᵀλ,
// λ stays in its bounds), so the rule checks primal feasibility, complementarity and the
// duality gap at every evaluation and stops NLopt as soon as they are met.
//
// 2D friction: the same dual with y = (λ_N, λ_T) on the rows [B; T] (multiplier_set.hpp); Tresca's
// λ_T,i ∈ [−r_i, r_i] is a bound, so the problem keeps its form, and the rule adds the tangential
// natural-map residual. Coulomb: the fixed point of coulomb_fixed_point.hpp around it. 3D friction
// is refused (its registration's max_friction_directions = 1): its discs are not bounds. Tried and dropped, at tol 1e-10 on
// 8 to 40 nodes: the discs as NLopt inequality constraints (LD_CCSAQ, LD_MMA, LD_SLSQP, AUGLAG
// around L-BFGS) stalled between 1e-9 and 1e-5; L-BFGS on the square through Fong's elliptical
// grid map, or on polar coordinates (ρ ∈ [−r, r]) after a run on the square around each disc,
// stalled between 1e-9 and 1e-8 on 40 nodes.
#include "backends.hpp"

#ifdef CONTACTQP_HAVE_NLOPT  // set by CMake when NLopt was found (CONTACTQP_WITH_NLOPT)
#include <nlopt.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "backend_options.hpp"
#include "contactqp/backends/nlopt.hpp"
#include "contactqp/certificate.hpp"
#include "contactqp/errors.hpp"
#include "coulomb_fixed_point.hpp"
#include "multiplier_set.hpp"
#include "qp/friction_sets.hpp"
#include "qp/norms.hpp"

namespace contactqp::detail {
namespace {

// The algorithms on offer: gradient-based methods that honour bound constraints.
const std::pair<NloptOptions::Algorithm, const char*> kAlgorithmNames[] = {
    {NloptOptions::Algorithm::Lbfgs, "LD_LBFGS"},
    {NloptOptions::Algorithm::Ccsaq, "LD_CCSAQ"},
    {NloptOptions::Algorithm::Mma, "LD_MMA"},
    {NloptOptions::Algorithm::Slsqp, "LD_SLSQP"},
};

nlopt::algorithm native(NloptOptions::Algorithm algorithm) {
  switch (algorithm) {
    case NloptOptions::Algorithm::Lbfgs:
      return nlopt::LD_LBFGS;
    case NloptOptions::Algorithm::Ccsaq:
      return nlopt::LD_CCSAQ;
    case NloptOptions::Algorithm::Mma:
      return nlopt::LD_MMA;
    case NloptOptions::Algorithm::Slsqp:
      return nlopt::LD_SLSQP;
  }
  return nlopt::LD_LBFGS;
}

std::string name_of(NloptOptions::Algorithm algorithm) {
  for (const auto& [value, name] : kAlgorithmNames)
    if (value == algorithm) return name;
  return "unknown";
}

// The NLopt options with the backend options ("algorithm", "memory") applied.
NloptOptions effective_options(const SolveOptions& options) {
  NloptOptions nlopt = options.get<NloptOptions>();
  for (const auto& [key, value] : options_for(Backend::Nlopt, options.backend_options)) {
    const std::string field = option_field(key);
    if (key == "algorithm") {
      std::string valid, upper = value;
      std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
      bool known = false;
      for (const auto& [algorithm, name] : kAlgorithmNames) {
        valid += (valid.empty() ? "" : ", ") + std::string(name);
        if (upper == name) {
          nlopt.algorithm = algorithm;
          known = true;
        }
      }
      if (!known) throw InputError(field, "= \"" + value + "\": unknown NLopt algorithm; valid: " + valid);
    } else if (key == "memory") {
      nlopt.memory = parse_integer(value, field);
    } else {
      throw InputError(field, "= \"" + value + "\": not an nlopt option; valid: algorithm, memory" +
                                  " (address Ipopt's options as ipopt." + key + ")");
    }
  }
  require(nlopt.memory >= 0, "nlopt.memory", nlopt.memory, "must be ≥ 0 (0: NLopt's choice)");
  return nlopt;
}

// Everything one evaluation of the dual needs, and the best point seen so far. With (2D) friction
// the multipliers are y = (λ_N, λ_T) on the rows C = [B; T] (multiplier_set.hpp), λ_T,i in the
// interval [−r_i, r_i], a bound; NLopt sees only the free entries: the λ_T of nodes whose
// interval is {0} stay 0.
class Dual {
 public:
  Dual(const QuadraticProgram& qp, const MultiplierSet& set, const LinearSolver& K_factor, const SolveOptions& options)
      : qp_(qp), set_(set), K_factor_(K_factor), options_(options) {
    for (int j = 0; j < set.rows(); ++j)
      if (j < set.normal_rows() || set.radii()[(j - set.normal_rows()) / set.n_directions()] > 0) free.push_back(j);
  }

  struct Point {
    VectorXd lambda, r;  // y, and r = C u(y) − c = ∇θ(y)
    double residual = std::numeric_limits<double>::infinity();
  };

  // The certificate's primal feasibility, complementarity and duality gap at (u(λ), λ), all
  // relative, the largest of them: the stopping rule's residual. With friction also the
  // tangential natural-map residual, and the gap of Tresca's problem.
  Point evaluate(const VectorXd& lambda) {
    ++evaluations;
    // Warm-started from the last evaluation's u (an iterative solver of K then starts close).
    const VectorXd u = K_factor_.solve(VectorXd(qp_.f - set_.C().transpose() * lambda), last_u_);
    last_u_ = u;
    Point point{lambda, set_.C() * u - set_.c()};
    point.residual = set_.frictional() ? friction_residual(u, point) : frictionless_residual(u, point);
    if (!std::isfinite(point.residual)) point.residual = std::numeric_limits<double>::infinity();
    if (options_.observer) options_.observer(evaluations, u, set_.lambda(lambda));
    if (point.residual < best.residual) best = point;
    return point;
  }

  // −θ(λ) − (−θ(λ₀)), exactly, for the quadratic θ: −½ (λ − λ₀)ᵀ(r(λ₀) + r(λ)). Measured from
  // the start of the current run rather than as −θ itself, so that the differences a line
  // search compares are not lost in the round-off of a large constant.
  double objective(const Point& point) const {
    return -0.5 * scale * (point.lambda - origin.lambda).dot(origin.r + point.r);
  }

  // Starts a run at the best point: the objective is measured from there and scaled so that
  // its projected gradient there is 1. NLopt's L-BFGS stops when that gradient falls below a
  // fixed 1e-8, so every run gains at least eight orders of magnitude, whatever the units.
  void restart_from_best() {
    origin = best;
    double projected = 0;
    if (set_.frictional()) {
      projected = inf_norm(VectorXd(set_.project(origin.lambda + origin.r) - origin.lambda));
    } else {
      for (int i = 0; i < origin.r.size(); ++i)
        projected = std::max(projected, origin.lambda[i] > 0 ? std::abs(origin.r[i]) : std::max(0.0, origin.r[i]));
    }
    scale = projected > 0 ? 1.0 / projected : 1.0;
  }

  // y from NLopt's variables x (the free entries) and back.
  VectorXd full(const double* x) const {
    VectorXd y = VectorXd::Zero(set_.rows());
    for (size_t k = 0; k < free.size(); ++k) y[free[k]] = x[k];
    return y;
  }
  std::vector<double> reduced(const VectorXd& y) const {
    std::vector<double> x(free.size());
    for (size_t k = 0; k < free.size(); ++k) x[k] = y[free[k]];
    return x;
  }

  double tol() const { return options_.tol; }
  bool solver_ok() const { return K_factor_.ok(); }

  int evaluations = 0;
  Point best, origin;
  double scale = 1.0;               // of the objective and its gradient in the current run
  nlopt::opt* optimizer = nullptr;  // the run in progress, stopped once the rule is met
  std::vector<int> free;            // the entries of y NLopt varies

 private:
  double frictionless_residual(const VectorXd& u, const Point& point) const {
    const VectorXd& lambda = point.lambda;
    // certify()'s length scale without friction (also when every radius is 0).
    const double F = force_scale(qp_, u, lambda), L = std::max(inf_norm(u), inf_norm(VectorXd(qp_.B * u)));
    const double violation = point.r.size() ? std::max(0.0, point.r.maxCoeff()) : 0.0;
    const double complementarity = inf_norm(VectorXd(lambda.cwiseProduct(point.r)));
    const double lambda_scale = std::max(inf_norm(lambda), F);
    // With K u = f − Bᵀλ exactly, J(u) − θ(λ) = −λᵀ(Bu − g); the energy scale is certify()'s.
    const double uKu = u.dot(qp_.f - qp_.B.transpose() * lambda), fu = qp_.f.dot(u);
    const double J = 0.5 * uKu - fu, gap = -lambda.dot(point.r);
    const double energy = std::max({std::abs(J), std::abs(J - gap), 0.5 * std::abs(uKu), std::abs(fu)});
    return std::max(
        {relative(violation, L), relative(complementarity, lambda_scale * L), relative(std::abs(gap), energy)});
  }

  // The same measures with friction (certificate.hpp).
  double friction_residual(const VectorXd& u, const Point& point) const {
    const int m = set_.normal_rows();
    const VectorXd lambda = set_.lambda(point.lambda), lambda_t = set_.lambda_t(point.lambda);
    const VectorXd gap_rows = point.r.head(m), slip = point.r.tail(point.r.size() - m);
    const double F = force_scale(qp_, u, lambda, lambda_t), L = length_scale(qp_, u);
    const double violation = m ? std::max(0.0, gap_rows.maxCoeff()) : 0.0;
    const double complementarity = inf_norm(VectorXd(lambda.cwiseProduct(gap_rows)));
    const double dissipated = dissipation(qp_.friction, set_.radii(), slip);
    const double rho = F > 0 && L > 0 ? F / L : 1.0;
    const double tangential = natural_map_residual(qp_.friction, lambda_t, set_.radii(), slip, rho);
    // J(u) − θ(y) = −yᵀ(Cu − c) + Σ r_i ‖slip_i‖ when K u = f − Cᵀy.
    const double uKu = u.dot(qp_.f - set_.C().transpose() * point.lambda), fu = qp_.f.dot(u);
    const double J = 0.5 * uKu - fu + dissipated, gap = dissipated - point.lambda.dot(point.r);
    const double energy = std::max({std::abs(J), std::abs(J - gap), 0.5 * std::abs(uKu), std::abs(fu), dissipated});
    return std::max({relative(violation, L), relative(complementarity, std::max(inf_norm(lambda), F) * L),
                     relative(std::abs(gap), energy), relative(tangential, F)});
  }

  const QuadraticProgram& qp_;
  const MultiplierSet& set_;
  const LinearSolver& K_factor_;
  const SolveOptions& options_;
  VectorXd last_u_;  // empty before the first evaluation: no guess
};

// How one NLopt run ended, as NLopt's result code (exceptions of the C++ API included).
nlopt::result run(nlopt::opt& optimizer, std::vector<double>& x) {
  double value = 0;
  try {
    return optimizer.optimize(x, value);
  } catch (const nlopt::roundoff_limited&) {
    return nlopt::ROUNDOFF_LIMITED;
  } catch (const nlopt::forced_stop&) {
    return nlopt::FORCED_STOP;
  } catch (const std::bad_alloc&) {
    return nlopt::OUT_OF_MEMORY;
  } catch (const std::invalid_argument&) {
    return nlopt::INVALID_ARGS;
  } catch (const std::runtime_error&) {
    return nlopt::FAILURE;
  }
}

const char* name_of(nlopt::result code) {
  switch (code) {
    case nlopt::FAILURE:
      return "NLOPT_FAILURE";
    case nlopt::INVALID_ARGS:
      return "NLOPT_INVALID_ARGS";
    case nlopt::OUT_OF_MEMORY:
      return "NLOPT_OUT_OF_MEMORY";
    case nlopt::ROUNDOFF_LIMITED:
      return "NLOPT_ROUNDOFF_LIMITED";
    case nlopt::FORCED_STOP:
      return "NLOPT_FORCED_STOP";
    case nlopt::NUM_FAILURES:
      return "NLOPT_NUM_FAILURES";
    case nlopt::SUCCESS:
      return "NLOPT_SUCCESS";
    case nlopt::STOPVAL_REACHED:
      return "NLOPT_STOPVAL_REACHED";
    case nlopt::FTOL_REACHED:
      return "NLOPT_FTOL_REACHED";
    case nlopt::XTOL_REACHED:
      return "NLOPT_XTOL_REACHED";
    case nlopt::MAXEVAL_REACHED:
      return "NLOPT_MAXEVAL_REACHED";
    case nlopt::MAXTIME_REACHED:
      return "NLOPT_MAXTIME_REACHED";
    case nlopt::NUM_RESULTS:
      return "NLOPT_NUM_RESULTS";
  }
  return "an unknown NLopt result";
}

// What to do after a run that ended with `code` without meeting our rule. NLopt's own
// stopping tests (all disabled) and round-off in its line search end a run early near the
// optimum; a restart from the best point, measuring the objective from there, goes on.
enum class Next { Restart, MaxIterations, Fail };

Next next_after(nlopt::result code) {
  switch (code) {
    case nlopt::SUCCESS:
    case nlopt::STOPVAL_REACHED:
    case nlopt::FTOL_REACHED:
    case nlopt::XTOL_REACHED:
    case nlopt::ROUNDOFF_LIMITED:
      return Next::Restart;
    case nlopt::FORCED_STOP:  // only our rule forces a stop: this one came from elsewhere
      return Next::Fail;
    case nlopt::MAXEVAL_REACHED:
    case nlopt::MAXTIME_REACHED:
      return Next::MaxIterations;
    case nlopt::FAILURE:
    case nlopt::INVALID_ARGS:
    case nlopt::OUT_OF_MEMORY:
    case nlopt::NUM_FAILURES:
    case nlopt::NUM_RESULTS:
      return Next::Fail;
  }
  return Next::Fail;
}

// A run counts as progress when it brings the best residual down by this factor; after this
// many runs in a row without progress the runs have stalled in round-off, and the backend
// reports what it reached.
constexpr double kRestartProgress = 0.5;
constexpr int kMaxRunsWithoutProgress = 3;

void check_nlopt_options(const SolveOptions& options) { effective_options(options); }

SolveResult solve_nlopt_once(const QuadraticProgram& qp, const VectorXd& radii, const SolveOptions& options,
                             const NloptOptions& settings) {
  const MultiplierSet set(qp, radii);
  const VectorXd warm = initial_multipliers(qp, options, set);
  SolveResult result;
  const int m = qp.n_constraints();
  result.K_factor = factor_of_K(qp, options, result.timings, result.message);
  if (!result.K_factor) return result;

  Stopwatch solve_clock;
  Dual dual(qp, set, *result.K_factor, options);
  const int n_free = static_cast<int>(dual.free.size());
  // Bounds: λ_N ≥ 0 and, with (2D) friction, λ_T,i ∈ [−r_i, r_i].
  std::vector<double> lower(n_free, 0.0), upper(n_free, HUGE_VAL);
  for (int k = 0; k < n_free; ++k) {
    const int j = dual.free[k];
    if (j < m) continue;
    lower[k] = -set.radii()[j - m];
    upper[k] = set.radii()[j - m];
  }
  dual.evaluate(warm.size() ? warm : VectorXd(VectorXd::Zero(set.rows())));
  bool converged = dual.best.residual <= options.tol;
  nlopt::result last = nlopt::SUCCESS;
  Next next = Next::Restart;
  int runs = 0, runs_without_progress = 0;

  while (!converged && n_free > 0 && next == Next::Restart) {
    const int remaining = options.max_iterations - dual.evaluations;
    if (remaining <= 0) {
      next = Next::MaxIterations;
      break;
    }
    const double residual_before = dual.best.residual;
    dual.restart_from_best();
    nlopt::opt optimizer(native(settings.algorithm), static_cast<unsigned>(n_free));
    if (set.frictional()) {
      optimizer.set_lower_bounds(lower);
      optimizer.set_upper_bounds(upper);
    } else {
      optimizer.set_lower_bounds(0.0);
    }
    optimizer.set_maxeval(remaining);
    if (settings.memory > 0) optimizer.set_vector_storage(static_cast<unsigned>(settings.memory));
    optimizer.set_min_objective(
        [](unsigned n, const double* x, double* gradient, void* data) {
          Dual& dual = *static_cast<Dual*>(data);
          const Dual::Point point = dual.evaluate(dual.full(x));
          if (gradient)
            for (unsigned k = 0; k < n; ++k) gradient[k] = -dual.scale * point.r[dual.free[k]];  // ∇(−θ)
          if (point.residual <= dual.tol() && dual.optimizer) dual.optimizer->force_stop();      // our rule is met
          if (!dual.solver_ok() && dual.optimizer) dual.optimizer->force_stop();  // a solve with K failed
          return dual.objective(point);
        },
        &dual);
    std::vector<double> x = dual.reduced(dual.origin.lambda);
    // NLopt refuses a start outside its bounds (NLOPT_INVALID_ARGS): a disc's radial projection
    // may land an ulp outside the interval.
    if (set.frictional())
      for (int k = 0; k < n_free; ++k) x[k] = std::clamp(x[k], lower[k], upper[k]);
    dual.optimizer = &optimizer;
    last = run(optimizer, x);
    ++runs;
    converged = dual.best.residual <= options.tol;
    if (!converged) {
      next = next_after(last);
      runs_without_progress = dual.best.residual < kRestartProgress * residual_before ? 0 : runs_without_progress + 1;
      if (next == Next::Restart && runs_without_progress >= kMaxRunsWithoutProgress) next = Next::Fail;
    }
  }
  result.timings.add("solve", solve_clock.seconds());

  // u from the final λ, with one more solve.
  const VectorXd& y = dual.best.lambda;
  result.lambda = set.lambda(y);
  result.lambda_t = set.lambda_t(y);
  result.u = result.K_factor->solve(VectorXd(qp.f - set.C().transpose() * y));
  result.iterations = dual.evaluations;
  result.diagnostics["nlopt_runs"] = runs;
  const std::string algorithm = name_of(settings.algorithm);
  if (!result.K_factor->ok()) {
    result.status = Status::NumericalError;
    result.message = algorithm + " on the dual stopped after " + std::to_string(dual.evaluations) +
                     " evaluations: a solve with K failed: " + result.K_factor->message();
  } else if (converged) {
    result.status = Status::Converged;
    result.message = "converged: " + algorithm + " on the dual; primal violation, complementarity" +
                     (set.frictional() ? ", the tangential condition" : "") + " and duality gap below " +
                     short_number(options.tol) + " after " + std::to_string(dual.evaluations) + " evaluations";
  } else if (next == Next::MaxIterations) {
    result.status = Status::MaxIterations;
    result.message = algorithm + " stopped after " + std::to_string(dual.evaluations) + " evaluations (" +
                     name_of(last) + ") with residual " + short_number(dual.best.residual) + "; raise max_iterations";
  } else {
    result.status = Status::NumericalError;
    result.message = algorithm + " stalled at residual " + short_number(dual.best.residual) + " (" + name_of(last) +
                     ") after " + std::to_string(dual.evaluations) +
                     " evaluations; try a larger tol or another algorithm";
  }
  return result;
}

SolveResult solve_nlopt(const QuadraticProgram& qp, const SolveOptions& options) {
  const NloptOptions settings = effective_options(options);
  if (qp.friction.law == FrictionLaw::Coulomb && !without_friction_force(qp.friction))
    return solve_coulomb_by_fixed_point(qp, options, [&](const VectorXd& radii, const SolveOptions& step_options) {
      return solve_nlopt_once(qp, radii, step_options, settings);
    });
  return solve_nlopt_once(qp, qp.friction.threshold, options, settings);
}

}  // namespace
}  // namespace contactqp::detail
#endif  // CONTACTQP_HAVE_NLOPT

CONTACTQP_BUILTIN(nlopt) {
  BackendRegistration nlopt;
  nlopt.name = "nlopt";
  nlopt.summary = "the dual by a bound-constrained NLopt method (L-BFGS by default)";
  nlopt.order = 40;
  nlopt.option_names = {"algorithm", "memory"};
#ifdef CONTACTQP_HAVE_NLOPT
  nlopt.check_options = check_nlopt_options;
  nlopt.solve = solve_nlopt;
  nlopt.problem_kinds = {ProblemKind::Frictionless, ProblemKind::Tresca, ProblemKind::Coulomb};
  nlopt.max_friction_directions = 1;  // 2D: the interval is a bound, the disc is not
#else
  nlopt.available = false;
#endif
  register_backend(nlopt);
}
