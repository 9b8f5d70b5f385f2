// solve(): what every backend shares — input validation, internal scaling, the hand-over to the
// backend's registration (backend.hpp), and the final guard against non-finite output — and the
// solver of K a backend works with.
#include <algorithm>
#include <cmath>

#include "backend_options.hpp"
#include "backends.hpp"
#include "cleanup.hpp"
#include "contactqp/backend.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/solve.hpp"
#include "qp/words.hpp"
#include "scaling.hpp"
#include "solve_steps.hpp"

namespace contactqp {
namespace detail {

LinearSolverOptions linear_solver_options(const QuadraticProgram& qp, const SolveOptions& options) {
  LinearSolverOptions settings;
  settings.kind = options.linear_solver;
  settings.ordering = options.ordering;
  settings.tol = options.tol;
  settings.library_options = options.library_options;
  settings.near_null_space = qp.near_null_space;
  settings.coarse_space = qp.coarse_space;
  settings.verbose = options.verbose;
  return settings;
}

std::shared_ptr<const LinearSolver> factor_of_K(const QuadraticProgram& qp, const SolveOptions& options,
                                                Timings& timings, std::string& message) {
  if (options.K_factor) return options.K_factor;
  Stopwatch clock;
  std::shared_ptr<const LinearSolver> factor = make_linear_solver(qp.K, linear_solver_options(qp, options));
  timings.add("factorize", clock.seconds());
  if (!factor->ok()) {
    // A K that is not positive definite is most often a body free to move rigidly: say so then.
    const bool indefinite = factor->message().find("not positive definite") != std::string::npos;
    message =
        options.linear_solver == LinearSolverKind::Cholmod
            ? "the stiffness matrix K could not be factorised: " + factor->message() +
                  (indefinite ? " (is the body restrained against rigid motion?)" : "")
            : "the " + to_string(options.linear_solver) + " solver of K could not be set up: " + factor->message();
    return nullptr;
  }
  return factor;
}

void report_linear_solver(SolveResult& result) {
  if (!result.K_factor) return;
  // An iterative solver of K: its inner (Krylov) iterations and solves since its set-up.
  const LinearSolverStatistics statistics = result.K_factor->statistics();
  if (statistics.iterations > 0) {
    result.diagnostics["krylov_iterations"] = static_cast<double>(statistics.iterations);
    result.diagnostics["linear_solves"] = static_cast<double>(statistics.solves);
  }
  for (const std::string& warning : result.K_factor->warnings()) result.warnings.push_back(warning);
}

namespace {

// The check of a backend that registered no check_options: every key addressed to it must be
// one of its option_names.
void check_option_names(const BackendRegistration& registration, const SolveOptions& options) {
  const Backend backend = options.backend;
  for (const auto& [key, value] : options_for(backend, options.backend_options)) {
    if (std::find(registration.option_names.begin(), registration.option_names.end(), key) !=
        registration.option_names.end())
      continue;
    if (registration.option_names.empty())
      reject_options(backend, options.backend_options, "address other backends' options as <backend>.key=value");
    const std::string hint = nearest(key, registration.option_names);
    throw InputError(option_field(key), "= \"" + value + "\": not an option of " + registration.name +
                                            "; valid: " + join(registration.option_names) +
                                            (hint.empty() ? "" : "; did you mean \"" + hint + "\"?"));
  }
}

// solve() refuses a problem its backend does not solve, naming the backends that do.
void check_problem_kind(const BackendRegistration& registration, const QuadraticProgram& qp) {
  const ProblemKind kind = problem_kind(qp);
  const bool kind_solved = std::find(registration.problem_kinds.begin(), registration.problem_kinds.end(), kind) !=
                           registration.problem_kinds.end();
  if (kind_solved && !qp.friction.empty() && qp.friction.n_directions > registration.max_friction_directions) {
    std::vector<std::string> others;
    for (Backend other : available_backends(qp)) others.push_back(to_string(other));
    throw InputError("backend", "= \"" + registration.name + "\": does not solve 3D " + to_string(kind) +
                                    " problems (2D only); backends that do: " + join(others));
  }
  if (kind_solved) return;
  std::vector<std::string> solved, others;
  for (ProblemKind k : registration.problem_kinds) solved.push_back(to_string(k));
  for (Backend other : available_backends(kind)) others.push_back(to_string(other));
  throw InputError("backend",
                   "= \"" + registration.name + "\": does not solve " + to_string(kind) + " problems (it solves " +
                       join(solved) + "); " +
                       (others.empty() ? "no backend built into this copy does" : "backends that do: " + join(others)));
}

void check_solve_options(const SolveOptions& options) {
  require(options.tol > 0 && options.tol < 1, "tol", options.tol, "must lie in (0, 1)");
  require(options.max_iterations > 0, "max_iterations", options.max_iterations, "must be positive");
  const UzawaOptions& uzawa = options.uzawa;
  if (uzawa.rho_rule != UzawaOptions::RhoRule::Auto)
    require(uzawa.rho > 0 && std::isfinite(uzawa.rho), "rho", uzawa.rho, "must be a positive number");
  require(options.active_set.max_dense_bytes > 0, "active_set.max_dense_bytes", options.active_set.max_dense_bytes,
          "must be positive");
  const std::shared_ptr<const BackendRegistration> registration = backend_registration(options.backend);
  require(registration->available, "backend", to_string(options.backend), "was not built into this copy of contactqp");
  require(linear_solver_available(options.linear_solver), "linear_solver", to_string(options.linear_solver),
          "was not built into this copy of contactqp (its library was absent at configure time)");
  if (registration->check_options)
    registration->check_options(options);
  else
    check_option_names(*registration, options);
}

}  // namespace

KOperations whole_K(const QuadraticProgram& qp) {
  return {[&qp](const VectorXd& u) { return K_times(qp, u); }, [&qp]() { return VectorXd(qp.K.diagonal()); }};
}

SolveResult solve_with(const QuadraticProgram& qp, const SolveOptions& options, const KOperations& K,
                       const BackendSolve& backend_solve) {
  validate(qp);
  check_solve_options(options);
  const std::shared_ptr<const BackendRegistration> registration = backend_registration(options.backend);
  check_problem_kind(*registration, qp);
  Stopwatch clock;

  // A frictional problem left at the default limit gets the backend's own, when larger.
  const bool raised = !qp.friction.empty() && options.max_iterations == kDefaultMaxIterations &&
                      registration->friction_max_iterations > kDefaultMaxIterations;
  SolveOptions limited;
  if (raised) {
    limited = options;
    limited.max_iterations = registration->friction_max_iterations;
  }
  const SolveOptions& used = raised ? limited : options;

  SolveResult result;
  if (used.scale) {
    const QpScaling scaling = choose_scaling(qp, K.diagonal());
    result = backend_solve(scaled_qp(qp, scaling), scaled_options(used, scaling));
    unscale_result(result, scaling);
  } else {
    result = backend_solve(qp, used);
  }
  if (raised) result.diagnostics["max_iterations"] = used.max_iterations;  // what the JSON's solver block reports

  // The final guard: no NaN or Inf ever leaves solve(), nor numbers whose energy overflows.
  // With friction λ_T has m · n_directions entries; without, none.
  const long t_rows = qp.friction.empty() ? 0 : qp.friction.T.rows();
  if (result.u.size() != qp.n_dofs() || !result.u.allFinite() || result.lambda.size() != qp.n_constraints() ||
      !result.lambda.allFinite() || result.lambda_t.size() != t_rows || !result.lambda_t.allFinite()) {
    if (result.status == Status::Converged) {
      result.status = Status::NumericalError;
      result.message = "the backend returned a solution that is not finite";
    }
    result.u = VectorXd::Zero(qp.n_dofs());
    result.lambda = VectorXd::Zero(qp.n_constraints());
    result.lambda_t = VectorXd::Zero(t_rows);
  } else if (overflows(qp, K.times, result)) {
    if (result.status == Status::Converged) result.status = Status::NumericalError;
    result.message += "; its last iterate overflows (energy beyond double range) and is reported as u = 0, λ = 0";
    result.u = VectorXd::Zero(qp.n_dofs());
    result.lambda = VectorXd::Zero(qp.n_constraints());
    result.lambda_t = VectorXd::Zero(t_rows);
  }
  zero_separated_multipliers(qp, K.times, result, options.tol);
  report_linear_solver(result);
  // A diagnostic that is not finite (ρ_max with no constraints) is absent, not Inf.
  for (auto it = result.diagnostics.begin(); it != result.diagnostics.end();)
    it = std::isfinite(it->second) ? std::next(it) : result.diagnostics.erase(it);
  result.timings.add("total", clock.seconds());
  return result;
}

}  // namespace detail

void validate_options(const SolveOptions& options) { detail::check_solve_options(options); }

SolveResult solve(const QuadraticProgram& qp, const SolveOptions& options) {
  // The backend's registration is looked up once the options are valid (its name among them).
  return detail::solve_with(qp, options, detail::whole_K(qp),
                            [&options](const QuadraticProgram& q, const SolveOptions& o) {
                              return backend_registration(options.backend)->solve(q, o);
                            });
}

}  // namespace contactqp
