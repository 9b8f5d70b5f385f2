// The primal interior-point backend: Ipopt (with Debian's sequential MUMPS) on the QP itself,
//
//   minimise ½ xᵀKx − fᵀx   subject to   −∞ ≤ B x ≤ g      (n variables, m inequalities).
//
// The Hessian of the Lagrangian is K (its lower triangle, constant) and the constraint
// Jacobian is B (constant); Ipopt is told both, so it evaluates them once. Ipopt's Lagrangian
// is f(x) + λᵀg(x) with λ ≥ 0 at an active upper bound: exactly our λ.
//
// Ipopt factorises the whole KKT matrix with MUMPS at every iteration and never needs K's
// Cholesky factor, so SolveResult::K_factor stays null (certify() factorises K itself).
//
// Built into the Ipopt plugin (ipopt_plugin.hpp); the backend's registration is solvers/ipopt.cpp.
#include "ipopt_solve.hpp"

#include <IpDenseVector.hpp>
#include <IpIpoptApplication.hpp>
#include <IpIpoptData.hpp>
#include <IpIteratesVector.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include "backend_options.hpp"
#include "backends.hpp"
#include "contactqp/errors.hpp"
#include "coulomb_fixed_point.hpp"
#include "ipopt_friction.hpp"
#include "multiplier_set.hpp"
#include "qp/friction_sets.hpp"
#include "qp/no_solution.hpp"

namespace contactqp::detail {
namespace {

using Ipopt::Index;
using Ipopt::Number;

// Debian's Ipopt links the sequential MUMPS, whose global state makes two concurrent solves in
// one process crash: every use of Ipopt in this process holds this lock.
std::mutex& ipopt_mutex() {
  static std::mutex mutex;
  return mutex;
}

// The QP as Ipopt's TNLP. The sparsity patterns are fixed here, once.
class QpNlp : public ContactNlp {
 public:
  QpNlp(const QuadraticProgram& qp, const SolveOptions& options)
      : qp_(qp),
        K_lower_(qp.K.triangularView<Eigen::Lower>()),
        observer_(options.observer),
        longest_(longest_carried_length(qp)) {
    n_inequalities = qp.n_constraints();
  }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& index_style) override {
    n = qp_.n_dofs();
    m = qp_.n_constraints();
    nnz_jac_g = static_cast<Index>(qp_.B.nonZeros());
    nnz_h_lag = static_cast<Index>(K_lower_.nonZeros());
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) override {
    std::fill(x_l, x_l + n, -kNoBound);
    std::fill(x_u, x_u + n, kNoBound);
    std::fill(g_l, g_l + m, -kNoBound);
    std::copy(qp_.g.data(), qp_.g.data() + m, g_u);
    return true;
  }

  bool get_constraints_linearity(Index m, LinearityType* types) override {
    std::fill(types, types + m, LINEAR);
    return true;
  }

  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number*, Number*, Index, bool init_lambda,
                          Number*) override {
    // u = 0 satisfies every row whose gap is not negative; Ipopt pushes it inside the bounds.
    if (init_x) std::fill(x, x + n, 0.0);
    return !init_z && !init_lambda;  // no multipliers to offer
  }

  bool eval_f(Index n, const Number* x, bool, Number& value) override {
    const Eigen::Map<const VectorXd> u(x, n);
    value = 0.5 * u.dot(qp_.K * u) - qp_.f.dot(u);
    return true;
  }

  bool eval_grad_f(Index n, const Number* x, bool, Number* gradient) override {
    const Eigen::Map<const VectorXd> u(x, n);
    Eigen::Map<VectorXd>(gradient, n) = qp_.K * u - qp_.f;
    return true;
  }

  bool eval_g(Index n, const Number* x, bool, Index m, Number* g) override {
    Eigen::Map<VectorXd>(g, m) = qp_.B * Eigen::Map<const VectorXd>(x, n);
    return true;
  }

  bool eval_jac_g(Index, const Number*, bool, Index, Index, Index* rows, Index* cols, Number* values) override {
    copy_entries(qp_.B, rows, cols, values, 1.0);
    return true;
  }

  // The Lagrangian's Hessian is obj_factor·K: the constraints are linear.
  bool eval_h(Index, const Number*, bool, Number obj_factor, Index, const Number*, bool, Index, Index* rows,
              Index* cols, Number* values) override {
    copy_entries(K_lower_, rows, cols, values, obj_factor);
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn, Index n, const Number* x, const Number*, const Number*, Index m,
                         const Number*, const Number* multipliers, Number, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    u = Eigen::Map<const VectorXd>(x, n);
    // Interior-point multipliers of inactive rows are tiny but positive; clipping only
    // removes round-off below zero.
    lambda = Eigen::Map<const VectorXd>(multipliers, m).cwiseMax(0.0);
    has_solution = true;
  }

  // Hands each iterate to the observer, and stops an iterate longer than any stiffness of K
  // carries: on a free motion the load drives, Ipopt's iterates reach ~1e16 and cycle in line
  // searches until max_iter (10000 iterations, 23 s on a three-mass chain) without reaching
  // its own diverging_iterates_tol (1e20). solve() then looks for the free motion. Ipopt 3.11
  // offers the iterate only in its internal form: x and the multipliers y_d of the
  // inequalities, which are ours because every row is an inequality, no variable is fixed, and
  // Ipopt's own NLP scaling is off (see below).
  bool intermediate_callback(Ipopt::AlgorithmMode mode, Index iteration, Number, Number, Number, Number, Number, Number,
                             Number, Number, Index, const Ipopt::IpoptData* data,
                             Ipopt::IpoptCalculatedQuantities*) override {
    if (mode != Ipopt::RegularMode || !data) return true;
    const auto* x = dynamic_cast<const Ipopt::DenseVector*>(Ipopt::GetRawPtr(data->curr()->x()));
    if (!x || x->Dim() != qp_.n_dofs()) return true;
    const Eigen::Map<const VectorXd> u_k(x->ExpandedValues(), x->Dim());
    if (u_k.size() > 0 && u_k.cwiseAbs().maxCoeff() > longest_) {
      diverged = true;
      return false;
    }
    if (!observer_ || !observe_) return true;
    const auto* y_d = dynamic_cast<const Ipopt::DenseVector*>(Ipopt::GetRawPtr(data->curr()->y_d()));
    if (!y_d || y_d->Dim() != qp_.n_constraints()) return true;
    const VectorXd lambda_k = Eigen::Map<const VectorXd>(y_d->ExpandedValues(), y_d->Dim()).cwiseMax(0.0);
    observer_(iteration + 1, u_k, lambda_k);
    return true;
  }

  void disable_observer() override { observe_ = false; }

 private:
  const QuadraticProgram& qp_;
  const SparseMatrix K_lower_;
  std::function<void(int, const VectorXd&, const VectorXd&)> observer_;
  bool observe_ = true;
  const double longest_;  // longest_carried_length(qp)
};

std::string describe_range(const Ipopt::RegisteredOption& option) {
  // Integer bounds are inclusive; Ipopt sets the strictness flags only for number options and
  // leaves them uninitialised otherwise (reading them is undefined: UBSan caught it).
  const bool number = option.Type() == Ipopt::OT_Number;
  std::string text;
  if (option.HasLower())
    text += (number && option.LowerStrict() ? "> " : ">= ") +
            short_number(number ? option.LowerNumber() : option.LowerInteger());
  if (option.HasUpper())
    text += std::string(text.empty() ? "" : " and ") + (number && option.UpperStrict() ? "< " : "<= ") +
            short_number(number ? option.UpperNumber() : option.UpperInteger());
  return text;
}

// Sets one option from text, with the type Ipopt's registry gives it. Checks first, so that
// Ipopt never prints a complaint of its own: bad keys and values are InputErrors.
void set_option(Ipopt::IpoptApplication& app, const std::string& key, const std::string& value) {
  const std::string field = option_field(key);
  const Ipopt::SmartPtr<const Ipopt::RegisteredOption> option = app.RegOptions()->GetOption(key);
  if (!Ipopt::IsValid(option))
    throw InputError(field, "= \"" + value + "\": not an Ipopt option (Ipopt's options reference lists them)");
  switch (option->Type()) {
    case Ipopt::OT_Number: {
      const double number = parse_number(value, field);
      if (!option->IsValidNumberSetting(number))
        throw InputError(field, "= " + value + ": Ipopt requires " + describe_range(*option));
      app.Options()->SetNumericValue(key, number);
      return;
    }
    case Ipopt::OT_Integer: {
      const int number = parse_integer(value, field);
      if (!option->IsValidIntegerSetting(number))
        throw InputError(field, "= " + value + ": Ipopt requires " + describe_range(*option));
      app.Options()->SetIntegerValue(key, number);
      return;
    }
    case Ipopt::OT_String: {
      if (!option->IsValidStringSetting(value)) {
        std::string valid;
        for (const auto& entry : option->GetValidStrings()) valid += (valid.empty() ? "" : ", ") + entry.value_;
        throw InputError(field, "= \"" + value + "\": valid: " + valid);
      }
      app.Options()->SetStringValue(key, value);
      return;
    }
    case Ipopt::OT_Unknown:
      break;
  }
  throw InputError(field, "= \"" + value + "\": Ipopt registers this option without a type");
}

// Options that change Ipopt's scaling of the NLP also change the internal iterate the
// observer would see: with these set by the user, the observer is not called.
bool changes_internal_scaling(const std::string& key) {
  return key == "nlp_scaling_method" || key == "obj_scaling_factor";
}

// Our settings first, then the user's (which win). Must happen before Initialize(), which
// reads print_level to set up the console.
// `nlp` is the problem Ipopt will solve (null when only the options are checked).
void configure(Ipopt::IpoptApplication& app, const QuadraticProgram& qp, const SolveOptions& options,
               const OptionMap& user, const ContactNlp* nlp) {
  // The frictional dual (ipopt_friction.hpp) has n linear equalities in force units and, in 3D,
  // quadratic disc constraints whose Jacobian and multiplier-weighted Hessian change.
  const bool dual = nlp && !dynamic_cast<const QpNlp*>(nlp);
  const bool curved = dual && qp.friction.n_directions == 2;
  Ipopt::OptionsList& list = *app.Options();
  // Never read ./ipopt.opt from whatever directory the program runs in.
  list.SetStringValue("option_file_name", "");
  if (!options.verbose) {
    list.SetIntegerValue("print_level", 0);
    list.SetStringValue("sb", "yes");  // the banner, printed even at print_level 0
  }
  list.SetStringValue("hessian_constant", curved ? "no" : "yes");
  list.SetStringValue("jac_c_constant", "yes");
  list.SetStringValue("jac_d_constant", curved ? "no" : "yes");
  // The default 1e-8 relaxes g to g + 1e-8·max(1, |g|), which moves the solution by as much.
  list.SetNumericValue("bound_relax_factor", 0.0);
  // solve() has already scaled the QP to numbers of order one; Ipopt's gradient-based scaling
  // would only make its tolerances mean something else.
  list.SetStringValue("nlp_scaling_method", "none");

  // Tolerances, so that the certificate's relative residuals come out at options.tol. Ipopt's
  // dual_inf_tol, constr_viol_tol and compl_inf_tol are absolute: scale them by a force F₀,
  // a length L₀ = F₀/κ and an energy F₀·L₀ of this QP (all 1 for a QP that solve() scaled).
  // The duality gap J − θ ≈ Σλᵢ(g − Bu)ᵢ sums the m complementarity products, which an
  // interior point keeps at about the same size: ask each for 1/m of the tolerance.
  double kappa = qp.n_dofs() ? qp.K.diagonal().cwiseAbs().maxCoeff() : 1.0;
  if (!(kappa > 0 && std::isfinite(kappa))) kappa = 1.0;
  double F0 = inf_norm(qp.f);
  if (!(F0 > 0)) F0 = kappa * inf_norm(qp.g);    // no load: the force that closes the gaps
  if (!(F0 > 0 && std::isfinite(F0))) F0 = 1.0;  // nothing to measure by
  const double L0 = F0 / kappa;
  const double tol = options.tol;
  // Ipopt refuses a tolerance of 0, which an underflow could produce in extreme units.
  auto positive = [](double x) { return std::max(x, std::numeric_limits<double>::min()); };
  list.SetNumericValue("tol", tol);
  list.SetNumericValue("dual_inf_tol", positive(tol * F0));
  list.SetNumericValue("constr_viol_tol", positive(tol * (dual ? F0 : L0)));  // the dual's rows are forces
  const int inequalities = nlp ? nlp->n_inequalities : qp.n_constraints();
  list.SetNumericValue("compl_inf_tol", positive(tol / std::max(1, inequalities) * F0 * L0));
  // Stopping at a merely "acceptable" point after a few slow iterations would return
  // something less accurate than asked for: only the requested tolerances count.
  list.SetIntegerValue("acceptable_iter", 0);
  list.SetIntegerValue("max_iter", options.max_iterations);
  list.SetStringValue("mu_strategy", "adaptive");

  for (const auto& [key, value] : user) set_option(app, key, value);
}

struct Outcome {
  Status status;
  const char* name;
  const char* advice;
};

// Every ApplicationReturnStatus, mapped once.
Outcome outcome_of(Ipopt::ApplicationReturnStatus code) {
  using S = Status;
  switch (code) {
    case Ipopt::Solve_Succeeded:
      return {S::Converged, "Solve_Succeeded", ""};
    case Ipopt::Solved_To_Acceptable_Level:
      return {S::NumericalError, "Solved_To_Acceptable_Level",
              "only Ipopt's acceptable tolerances were met; round-off limits the accuracy, try a larger tol"};
    case Ipopt::Infeasible_Problem_Detected:
      return {S::NumericalError, "Infeasible_Problem_Detected", "the contact constraints admit no displacement"};
    case Ipopt::Search_Direction_Becomes_Too_Small:
      return {S::NumericalError, "Search_Direction_Becomes_Too_Small",
              "no further progress in double precision; try a larger tol"};
    case Ipopt::Diverging_Iterates:
      return {S::Diverged, "Diverging_Iterates", "the iterates grew without bound"};
    case Ipopt::User_Requested_Stop:
      return {S::NumericalError, "User_Requested_Stop", "stopped by a callback"};
    case Ipopt::Feasible_Point_Found:
      return {S::NumericalError, "Feasible_Point_Found", "Ipopt only looked for a feasible point"};
    case Ipopt::Maximum_Iterations_Exceeded:
      return {S::MaxIterations, "Maximum_Iterations_Exceeded", "raise max_iterations"};
    case Ipopt::Restoration_Failed:
      return {S::NumericalError, "Restoration_Failed", "Ipopt's feasibility restoration failed"};
    case Ipopt::Error_In_Step_Computation:
      return {S::NumericalError, "Error_In_Step_Computation",
              "the KKT system could not be solved; is K positive definite?"};
    case Ipopt::Maximum_CpuTime_Exceeded:
      return {S::MaxIterations, "Maximum_CpuTime_Exceeded", "raise max_cpu_time"};
    case Ipopt::Not_Enough_Degrees_Of_Freedom:
      return {S::NumericalError, "Not_Enough_Degrees_Of_Freedom", "more equations than unknowns"};
    case Ipopt::Invalid_Problem_Definition:
      return {S::NumericalError, "Invalid_Problem_Definition", "Ipopt rejected the problem's data"};
    case Ipopt::Invalid_Option:
      return {S::NumericalError, "Invalid_Option",
              "an option was refused (linear solvers other than mumps are not in Debian's Ipopt)"};
    case Ipopt::Invalid_Number_Detected:
      return {S::NumericalError, "Invalid_Number_Detected", "a NaN or Inf appeared in the evaluations"};
    case Ipopt::Unrecoverable_Exception:
      return {S::NumericalError, "Unrecoverable_Exception", "Ipopt failed internally"};
    case Ipopt::NonIpopt_Exception_Thrown:
      return {S::NumericalError, "NonIpopt_Exception_Thrown", "an exception escaped an evaluation"};
    case Ipopt::Insufficient_Memory:
      return {S::NumericalError, "Insufficient_Memory",
              "MUMPS ran out of memory; a coarser mesh or a larger mumps_mem_percent may help"};
    case Ipopt::Internal_Error:
      return {S::NumericalError, "Internal_Error", "Ipopt failed internally"};
  }
  return {S::NumericalError, "an unknown return status", "Ipopt returned a code this version does not know"};
}

Ipopt::SmartPtr<Ipopt::IpoptApplication> configured_application(const QuadraticProgram& qp, const SolveOptions& options,
                                                                const ContactNlp* nlp = nullptr) {
  // Without the console journal nothing at all can be printed: keep it only when verbose.
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = new Ipopt::IpoptApplication(options.verbose);
  configure(*app, qp, options, options_for(Backend::Ipopt, options.backend_options), nlp);
  return app;
}

}  // namespace

void check_ipopt_options(const SolveOptions& options) {
  std::lock_guard<std::mutex> lock(ipopt_mutex());
  configured_application(QuadraticProgram{}, options);
}

namespace {

// One Ipopt solve: the primal QP without friction force, else the frictional dual with the
// discs' radii `radii`.
SolveResult solve_ipopt_once(const QuadraticProgram& qp, const VectorXd& radii, const SolveOptions& options) {
  std::lock_guard<std::mutex> lock(ipopt_mutex());
  SolveResult result;
  Stopwatch setup_clock;
  const bool frictional = radii.size() > 0 && radii.cwiseAbs().maxCoeff() > 0;
  Ipopt::SmartPtr<ContactNlp> nlp =
      frictional ? make_friction_dual_nlp(qp, radii) : Ipopt::SmartPtr<ContactNlp>(new QpNlp(qp, options));
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = configured_application(qp, options, Ipopt::GetRawPtr(nlp));
  for (const auto& [key, value] : options_for(Backend::Ipopt, options.backend_options))
    if (changes_internal_scaling(key)) nlp->disable_observer();
  const Ipopt::ApplicationReturnStatus initialized = app->Initialize();
  result.timings.add("setup", setup_clock.seconds());
  if (initialized != Ipopt::Solve_Succeeded) {
    result.message = "Ipopt could not be initialised: " + std::string(outcome_of(initialized).name);
    return result;
  }

  Stopwatch solve_clock;
  Ipopt::ApplicationReturnStatus code = Ipopt::Internal_Error;
  try {
    code = app->OptimizeTNLP(Ipopt::GetRawPtr(nlp));
  } catch (const std::bad_alloc&) {
    code = Ipopt::Insufficient_Memory;
  } catch (const std::exception&) {
    code = Ipopt::Unrecoverable_Exception;
  }
  result.timings.add("solve", solve_clock.seconds());

  const Outcome outcome =
      nlp->diverged ? Outcome{Status::Diverged, "stopped", "its iterate grew beyond what any stiffness of K carries"}
                    : outcome_of(code);
  result.status = outcome.status;
  if (Ipopt::IsValid(app->Statistics())) result.iterations = app->Statistics()->IterationCount();
  if (Ipopt::IsValid(app->IpoptDataObject())) {
    // Factorising and solving the KKT systems with MUMPS (Ipopt's MUMPS interface does not
    // time the factorisation on its own): nearly all of an Ipopt solve.
    result.diagnostics["kkt_solve_seconds"] =
        app->IpoptDataObject()->TimingStats().StdAugSystemSolverMultiSolve().TotalWallclockTime();
  }
  if (nlp->has_solution) {
    result.u = nlp->u;
    result.lambda = nlp->lambda;
    result.lambda_t = frictional ? nlp->lambda_t : VectorXd(VectorXd::Zero(qp.friction.T.rows()));
  } else {
    result.u = VectorXd::Zero(qp.n_dofs());
    result.lambda = VectorXd::Zero(qp.n_constraints());
    result.lambda_t = VectorXd::Zero(qp.friction.T.rows());
    if (result.status == Status::Converged) result.status = Status::NumericalError;
  }
  result.message = "Ipopt" + std::string(frictional ? " (Tresca's dual)" : "") + ": " + outcome.name + " after " +
                   std::to_string(result.iterations) + " iterations" +
                   (outcome.status == Status::Converged ? "" : std::string("; ") + outcome.advice);
  return result;
}

}  // namespace

SolveResult solve_ipopt(const QuadraticProgram& qp, const SolveOptions& options) {
  // An interior point gains little from a starting point near the answer: the warm start is
  // only checked, not used.
  initial_multipliers(qp, options, MultiplierSet(qp, qp.friction.threshold));
  if (qp.friction.law == FrictionLaw::Coulomb && !without_friction_force(qp.friction))
    return solve_coulomb_by_fixed_point(qp, options, [&](const VectorXd& radii, const SolveOptions& step_options) {
      return solve_ipopt_once(qp, radii, step_options);
    });
  return solve_ipopt_once(qp, qp.friction.threshold, options);
}

}  // namespace contactqp::detail
