// solve(): what every backend shares — input validation, internal scaling, the hand-over to the
// backend's registration (backend.hpp), and the final guard against non-finite output — and the
// solver of K a backend works with.
#include <algorithm>
#include <cmath>

#include "backend_options.hpp"
#include "backends.hpp"
#include "cleanup.hpp"
#include "contactqp/backend.hpp"
#include "contactqp/backends/active_set.hpp"
#include "contactqp/backends/uzawa.hpp"
#include "contactqp/certificate.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/number_format.hpp"
#include "contactqp/solve.hpp"
#include "floating.hpp"
#include "qp/no_solution.hpp"
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
  if (result.K_factor) report_linear_solver(result, result.K_factor->statistics());
}

void report_linear_solver(SolveResult& result, const LinearSolverStatistics& statistics) {
  if (!result.K_factor) return;
  // An iterative solver of K: its inner (Krylov) iterations and solves since its set-up.
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
  const UzawaOptions uzawa = options.get<UzawaOptions>();
  if (uzawa.rho_rule != UzawaOptions::RhoRule::Auto)
    require(uzawa.rho > 0 && std::isfinite(uzawa.rho), "rho", uzawa.rho, "must be a positive number");
  require(options.get<ActiveSetOptions>().max_dense_bytes > 0, "active_set.max_dense_bytes",
          options.get<ActiveSetOptions>().max_dense_bytes, "must be positive");
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
  KOperations K;
  K.times = [&qp](const VectorXd& u) { return K_times(qp, u); };
  K.diagonal = [&qp]() { return VectorXd(qp.K.diagonal()); };
  K.certify = [&qp](const VectorXd& u, const VectorXd& lambda, const VectorXd& lambda_t, const LinearSolver* K_factor) {
    return contactqp::certify(qp, u, lambda, lambda_t, K_factor);
  };
  K.like = [](const QuadraticProgram& other) { return whole_K(other); };
  return K;
}

Certificate certify_result(const KOperations& K, const SolveResult& result) {
  return K.certify(result.u, result.lambda, result.lambda_t, result.K_factor.get());
}

namespace {

// Whether u is so long that only a (numerically) free motion explains it (no_solution.hpp).
bool beyond_any_stiffness(const QuadraticProgram& qp, const VectorXd& u) {
  return u.size() > 0 && u.cwiseAbs().maxCoeff() > longest_carried_length(qp);
}

// The status never claims more than the certificate shows; where it rejects the answer, look for
// the evidence that no answer exists (rows that contradict each other, a free motion the load
// drives) and say what was found. `known`: K's null space when the QP carries it (else it is
// computed here). Returns the null space it used: n × 0 when it did not look or K is definite.
Eigen::MatrixXd certify_status(const QuadraticProgram& qp, const SolveOptions& options, const KOperations& K,
                               SolveResult& result, const Certificate& certificate, const Eigen::MatrixXd& known) {
  apply_certificate(result, certificate, options.tol);
  // On a K held in parts only a QP that carries its null space is searched (the evidence needs
  // only f, B, g and R, whole and alike on every process), and never a length judged against K.
  if (!K.whole && known.cols() == 0) return {};
  const bool beyond = K.whole && beyond_any_stiffness(qp, result.u);
  if (result.status == Status::Converged && !beyond) return {};
  if (beyond && result.status != Status::Converged) {
    // A last iterate that long is no answer to show (a free motion, or a solve that broke down).
    result.message += "; its last iterate (|u| up to " + short_number(result.u.cwiseAbs().maxCoeff()) +
                      ", beyond what any stiffness of K carries) is reported as u = 0, λ = 0";
    result.u.setZero();
    result.lambda.setZero();
    result.lambda_t.setZero();
    result.certificate = certify_result(K, result);
  }

  Stopwatch clock;
  const VectorXd farkas = farkas_direction(qp, options.tol);
  VectorXd recession;
  Eigen::MatrixXd R;
  if (farkas.size() == 0) {
    R = known.cols() > 0 ? known : qp.n_dofs() <= kNullSpaceMaxDofs ? null_space_of(qp.K) : Eigen::MatrixXd();
    result.null_space_dimension = static_cast<int>(R.cols());
    recession = recession_direction(qp, R);
    if (R.cols() > 0 && recession.size() == 0)
      result.message +=
          "; K is only positive semidefinite (" + std::to_string(R.cols()) + " free motions, which the rows must hold)";
  }
  if (farkas.size() > 0 || recession.size() > 0) {
    const bool infeasible = farkas.size() > 0;
    result.status = infeasible ? Status::Infeasible : Status::Unbounded;
    result.message =
        infeasible ? "infeasible: no u satisfies B u <= g (" + std::to_string((farkas.array() > 0).count()) +
                         " rows contradict each other; SolveResult::farkas is the evidence)"
                   : "unbounded: the load drives a free motion of K (null space of dimension " +
                         std::to_string(result.null_space_dimension) +
                         ") that no row stops, so the energy falls without bound along it (SolveResult::recession)";
    result.farkas = farkas;
    result.recession = recession;
    // No answer exists: report none rather than the backend's last iterate.
    result.u.setZero();
    result.lambda.setZero();
    result.lambda_t.setZero();
    result.certificate = certify_result(K, result);
  }
  result.timings.add("diagnose", clock.seconds());
  return R;
}

}  // namespace

namespace {

// The backend on the (scaled) problem, its answer back in the caller's units and guarded: no
// NaN or Inf ever leaves solve(), nor numbers whose energy overflows.
SolveResult run_backend(const QuadraticProgram& qp, const SolveOptions& used, const KOperations& K,
                        const BackendSolve& backend_solve) {
  SolveResult result;
  if (used.scale) {
    const QpScaling scaling = choose_scaling(qp, K.diagonal());
    result = backend_solve(scaled_qp(qp, scaling), scaled_options(used, scaling));
    unscale_result(result, scaling);
  } else {
    result = backend_solve(qp, used);
  }
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
  zero_separated_multipliers(qp, K.times, result, used.tol);
  return result;
}

// A backend's stopping test measures its own scaled copy, often a proxy of the certificate (a
// change of λ, Ipopt's scaled error, Coulomb's fixed point): when it claims Converged and the
// certificate disagrees, it gets one more run from its answer at a tolerance tightened by the
// certificate's excess, and the second answer is kept when the certificate accepts it.
void tighten_once(const QuadraticProgram& qp, const SolveOptions& used, const KOperations& K,
                  const BackendSolve& backend_solve, SolveResult& result, Certificate& certificate) {
  if (result.status != Status::Converged || meets_tolerance(certificate, used.tol)) return;
  const double excess =
      std::max(certificate.kkt_max(), certificate.dual_available ? std::abs(certificate.relative_gap) : 0.0);
  if (!std::isfinite(excess)) return;
  SolveOptions tighter = used;
  tighter.tol = std::max(1e-14, std::min(0.1 * used.tol, 0.1 * used.tol * kCertifiedFactor * used.tol / excess));
  tighter.initial = {result.u, result.lambda, result.lambda_t};
  if (result.K_factor) tighter.K_factor = result.K_factor;
  SolveResult again = run_backend(qp, tighter, K, backend_solve);
  const Certificate second = certify_result(K, again);
  // The second run's own test is at the tighter tol, which it may not reach (Ipopt's restoration
  // failing at 1e-12): its answer counts when the certificate accepts it at the caller's tol.
  if (!meets_tolerance(second, used.tol)) {
    result.message += "; a second run at tol " + short_number(tighter.tol) + " from its answer ended " +
                      to_string(again.status) + " with relative KKT residual " + short_number(second.kkt_max()) +
                      " (stationarity " + short_number(second.stationarity) + ", tangential " +
                      short_number(second.tangential) + ")";
    return;
  }
  again.iterations += result.iterations;
  Timings timings = result.timings;
  timings.merge(again.timings);
  again.timings = timings;
  again.diagnostics["tightened_tol"] = tighter.tol;
  again.message = result.message + "; the certificate rejected that answer, and a second run from it at tol " +
                  short_number(tighter.tol) + " (" + again.message + ") gave one it accepts";
  again.status = Status::Converged;
  result = std::move(again);
  certificate = second;
}

}  // namespace

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

  // A definite QP of the proximal steps on K's free modes (floating.hpp), run like the QP itself
  // (its K held as this one's: whole, or in the same parts).
  const DefiniteSolve definite = [&backend_solve, &K](const QuadraticProgram& q, const SolveOptions& o) {
    return run_backend(q, o, K.like(q), backend_solve);
  };
  // A QP that carries K's null space is solved on its free modes from the start.
  const bool free_modes = qp.null_space.cols() > 0 && K.like;
  const Eigen::MatrixXd R = free_modes ? orthonormal_null_space(qp.null_space, "qp.null_space") : Eigen::MatrixXd();

  SolveResult result;
  Certificate certificate;
  LinearSolverStatistics statistics;
  double certify_seconds = 0;
  if (free_modes) {
    result = solve_with_free_modes(qp, R, used, K, definite);  // certified inside, with K's generalised inverse
    result.null_space_dimension = static_cast<int>(R.cols());
    certificate = *result.certificate;
    statistics = result.K_factor ? result.K_factor->statistics() : LinearSolverStatistics{};
  } else {
    result = run_backend(qp, used, K, backend_solve);
    // The solver of K's statistics count the backend's solves, not the certificate's.
    statistics = result.K_factor ? result.K_factor->statistics() : LinearSolverStatistics{};
    Stopwatch certifying;
    certificate = certify_result(K, result);
    certify_seconds = certifying.seconds();
    tighten_once(qp, used, K, backend_solve, result, certificate);
    if (result.diagnostics.count("tightened_tol") && result.K_factor) statistics = result.K_factor->statistics();
  }
  if (raised) result.diagnostics["max_iterations"] = used.max_iterations;  // what the JSON's solver block reports
  report_linear_solver(result, statistics);
  result.timings.add("certify", certify_seconds);
  const Eigen::MatrixXd found = certify_status(qp, options, K, result, certificate, R);
  // K turned out only semidefinite, with free modes the rows can hold: solve on them.
  const bool no_answer = result.status == Status::Infeasible || result.status == Status::Unbounded;
  if (!free_modes && !no_answer && found.cols() > 0 &&
      (result.status != Status::Converged || beyond_any_stiffness(qp, result.u))) {
    SolveResult held = solve_with_free_modes(qp, found, used, K, definite);
    if (held.status == Status::Converged) {
      held.null_space_dimension = static_cast<int>(found.cols());
      held.message = "K is only positive semidefinite (" + std::to_string(found.cols()) +
                     " free motions, found from its eigenvalues after a first run ended " + to_string(result.status) +
                     "): " + held.message;
      Timings timings = result.timings;
      timings.merge(held.timings);
      held.timings = timings;
      held.iterations += result.iterations;
      report_linear_solver(held);
      result = std::move(held);
    }
  }
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
