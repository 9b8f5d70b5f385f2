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
#include "backends.hpp"

#ifdef CONTACTQP_HAVE_NLOPT  // set by CMake when NLopt was found (CONTACTQP_WITH_NLOPT)
#include <nlopt.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "backend_options.hpp"
#include "contactqp/certificate.hpp"
#include "contactqp/errors.hpp"
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
  NloptOptions nlopt = options.nlopt;
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

// Everything one evaluation of the dual needs, and the best point seen so far.
class Dual {
 public:
  Dual(const QuadraticProgram& qp, const LinearSolver& K_factor, const SolveOptions& options)
      : qp_(qp), K_factor_(K_factor), options_(options) {}

  struct Point {
    VectorXd lambda, r;  // r = B u(λ) − g = ∇θ(λ)
    double residual = std::numeric_limits<double>::infinity();
  };

  // The certificate's primal feasibility, complementarity and duality gap at (u(λ), λ), all
  // relative, the largest of them: the stopping rule's residual.
  Point evaluate(const VectorXd& lambda) {
    ++evaluations;
    // Warm-started from the last evaluation's u (an iterative solver of K then starts close).
    const VectorXd u = K_factor_.solve(VectorXd(qp_.f - qp_.B.transpose() * lambda), last_u_);
    last_u_ = u;
    Point point{lambda, qp_.B * u - qp_.g};
    const double F = force_scale(qp_, u, lambda), L = length_scale(qp_, u);
    const double violation = point.r.size() ? std::max(0.0, point.r.maxCoeff()) : 0.0;
    const double complementarity = inf_norm(VectorXd(lambda.cwiseProduct(point.r)));
    const double lambda_scale = std::max(inf_norm(lambda), F);
    // With K u = f − Bᵀλ exactly, J(u) − θ(λ) = −λᵀ(Bu − g); the energy scale is certify()'s.
    const double uKu = u.dot(qp_.f - qp_.B.transpose() * lambda), fu = qp_.f.dot(u);
    const double J = 0.5 * uKu - fu, gap = -lambda.dot(point.r);
    const double energy = std::max({std::abs(J), std::abs(J - gap), 0.5 * std::abs(uKu), std::abs(fu)});
    point.residual = std::max(
        {relative(violation, L), relative(complementarity, lambda_scale * L), relative(std::abs(gap), energy)});
    if (!std::isfinite(point.residual)) point.residual = std::numeric_limits<double>::infinity();
    if (options_.observer) options_.observer(evaluations, u, lambda);
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
    for (int i = 0; i < origin.r.size(); ++i)
      projected = std::max(projected, origin.lambda[i] > 0 ? std::abs(origin.r[i]) : std::max(0.0, origin.r[i]));
    scale = projected > 0 ? 1.0 / projected : 1.0;
  }

  double tol() const { return options_.tol; }
  bool solver_ok() const { return K_factor_.ok(); }

  int evaluations = 0;
  Point best, origin;
  double scale = 1.0;               // of the objective and its gradient in the current run
  nlopt::opt* optimizer = nullptr;  // the run in progress, stopped once the rule is met

 private:
  const QuadraticProgram& qp_;
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

SolveResult solve_nlopt(const QuadraticProgram& qp, const SolveOptions& options) {
  const NloptOptions settings = effective_options(options);
  SolveResult result;
  const int m = qp.n_constraints();
  result.K_factor = factor_of_K(qp, options, result.timings, result.message);
  if (!result.K_factor) return result;

  Stopwatch solve_clock;
  Dual dual(qp, *result.K_factor, options);
  dual.evaluate(VectorXd::Zero(m));
  bool converged = dual.best.residual <= options.tol;
  nlopt::result last = nlopt::SUCCESS;
  Next next = Next::Restart;
  int runs = 0, runs_without_progress = 0;

  while (!converged && m > 0 && next == Next::Restart) {
    const int remaining = options.max_iterations - dual.evaluations;
    if (remaining <= 0) {
      next = Next::MaxIterations;
      break;
    }
    const double residual_before = dual.best.residual;
    dual.restart_from_best();
    nlopt::opt optimizer(native(settings.algorithm), static_cast<unsigned>(m));
    optimizer.set_lower_bounds(0.0);
    optimizer.set_maxeval(remaining);
    if (settings.memory > 0) optimizer.set_vector_storage(static_cast<unsigned>(settings.memory));
    optimizer.set_min_objective(
        [](unsigned n, const double* x, double* gradient, void* data) {
          Dual& dual = *static_cast<Dual*>(data);
          const Dual::Point point = dual.evaluate(Eigen::Map<const VectorXd>(x, n));
          if (gradient) Eigen::Map<VectorXd>(gradient, n) = -dual.scale * point.r;           // ∇(−θ)
          if (point.residual <= dual.tol() && dual.optimizer) dual.optimizer->force_stop();  // our rule is met
          if (!dual.solver_ok() && dual.optimizer) dual.optimizer->force_stop();             // a solve with K failed
          return dual.objective(point);
        },
        &dual);
    std::vector<double> x(dual.origin.lambda.data(), dual.origin.lambda.data() + m);
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
  result.lambda = dual.best.lambda;
  result.u = result.K_factor->solve(VectorXd(qp.f - qp.B.transpose() * result.lambda));
  result.iterations = dual.evaluations;
  result.diagnostics["nlopt_runs"] = runs;
  const std::string algorithm = name_of(settings.algorithm);
  if (!result.K_factor->ok()) {
    result.status = Status::NumericalError;
    result.message = algorithm + " on the dual stopped after " + std::to_string(dual.evaluations) +
                     " evaluations: a solve with K failed: " + result.K_factor->message();
  } else if (converged) {
    result.status = Status::Converged;
    result.message = "converged: " + algorithm +
                     " on the dual; primal violation, complementarity and duality gap below " +
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
#else
  nlopt.available = false;
#endif
  register_backend(nlopt);
}
