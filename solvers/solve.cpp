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

namespace contactqp {
namespace detail {

LinearSolverOptions linear_solver_options(const QuadraticProgram& qp, const SolveOptions& options) {
  LinearSolverOptions settings;
  settings.kind = options.linear_solver;
  settings.ordering = options.ordering;
  settings.tol = options.tol;
  settings.petsc_options = options.petsc_options;
  settings.near_null_space = qp.near_null_space;
  settings.rank_share = qp.K_is_rank_share;
  settings.distributed_row = qp.distributed_row;
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
                                    " problems (2D only); backends that do: " +
                                    join(others));
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

void validate_options(const SolveOptions& options) {
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
          "was not built into this copy of contactqp (PETSc absent at configure time)");
  if (registration->check_options)
    registration->check_options(options);
  else
    check_option_names(*registration, options);
}

}  // namespace
}  // namespace detail

void validate_options(const SolveOptions& options) { detail::validate_options(options); }

SolveResult solve(const QuadraticProgram& qp, const SolveOptions& options) {
  validate(qp);
  detail::validate_options(options);
  const std::shared_ptr<const BackendRegistration> registration = backend_registration(options.backend);
  detail::check_problem_kind(*registration, qp);
  if (qp.K_is_rank_share && options.backend != Backend::Petsc)
    throw InputError("backend",
                     "= " + to_string(options.backend) +
                         ": K is assembled in shares over the MPI ranks, which only the petsc backend solves");
  // The shares are summed (scaling, certificate) by MPI, which PETSc starts.
  if (qp.K_is_rank_share) start_petsc_runtime(options.petsc_options);
  Stopwatch clock;

  SolveResult result;
  if (options.scale) {
    const detail::QpScaling scaling = detail::choose_scaling(qp);
    result = registration->solve(detail::scaled_qp(qp, scaling), detail::scaled_options(options, scaling));
    detail::unscale_result(result, scaling);
  } else {
    result = registration->solve(qp, options);
  }

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
  } else if (detail::overflows(qp, result)) {
    if (result.status == Status::Converged) result.status = Status::NumericalError;
    result.message += "; its last iterate overflows (energy beyond double range) and is reported as u = 0, λ = 0";
    result.u = VectorXd::Zero(qp.n_dofs());
    result.lambda = VectorXd::Zero(qp.n_constraints());
    result.lambda_t = VectorXd::Zero(t_rows);
  }
  detail::zero_separated_multipliers(qp, result, options.tol);
  detail::report_linear_solver(result);
  // A diagnostic that is not finite (ρ_max with no constraints) is absent, not Inf.
  for (auto it = result.diagnostics.begin(); it != result.diagnostics.end();)
    it = std::isfinite(it->second) ? std::next(it) : result.diagnostics.erase(it);
  result.timings.add("total", clock.seconds());
  return result;
}

}  // namespace contactqp
