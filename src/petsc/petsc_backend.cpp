// The petsc backend: the contact QP brought to bound form (bound_form.hpp) and solved by PETSc
// on the distributed matrix (petsc_bound_qp.cpp): a primal-dual active-set loop whose
// steps are KSP solves (CG + GAMG with the rigid-body modes) by default, TAO with
// method=tao. Use: docs/petsc.md; design: docs/petsc-design.md; figures: docs/petsc-measurements.md.
//
//   transform   A = QᵀKQ, b = Qᵀf; row i of Bu ≤ g becomes v_i ≤ g_i     (per node, Eigen)
//   iterate     the bound QP in PETSc, every rank holding its rows of A
//   recover     u = Q v, λ = μ
#include "petsc_backend.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <utility>

#include "backend_options.hpp"
#include "backends.hpp"
#include "bound_form.hpp"
#include "contactqp/certificate.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/processes.hpp"
#include "coulomb_fixed_point.hpp"
#include "mpi.hpp"
#include "multiplier_set.hpp"
#include "qp/friction_sets.hpp"
#include "qp/norms.hpp"

namespace contactqp::detail {
namespace {

// The backend options: method=pdas|tao; for pdas hierarchy=kept|fresh (one multigrid
// hierarchy for the whole solve, or a set-up per step), p1_start=true|false (kept: the P1
// contact problem first), inexact=true|false (loose early steps), loose_reduction=r (kept: a
// loose step's CG reduces its residual r times, 0 < r < 1) and, with fresh,
// reuse_preconditioner=true|false (a step's GAMG kept while its solves stay short).
BoundQpOptions backend_settings(const SolveOptions& options) {
  BoundQpOptions settings;
  for (const auto& [key, value] : options_for(Backend::Petsc, options.backend_options)) {
    if (key == "method") {
      if (value != "pdas" && value != "tao")
        throw InputError(option_field(key), "= \"" + value + "\": not a method of petsc; valid: pdas, tao");
      settings.method = value;
    } else if (key == "hierarchy") {
      if (value != "kept" && value != "fresh")
        throw InputError(option_field(key), "= \"" + value + "\": not a hierarchy of petsc; valid: kept, fresh");
      settings.kept_hierarchy = value == "kept";
    } else if (key == "inexact" || key == "reuse_preconditioner" || key == "p1_start") {
      if (value != "true" && value != "false" && value != "1" && value != "0")
        throw InputError(option_field(key), "= \"" + value + "\": not true or false");
      bool& flag = key == "inexact"    ? settings.inexact
                   : key == "p1_start" ? settings.p1_start
                                       : settings.reuse_preconditioner;
      flag = value == "true" || value == "1";
    } else if (key == "loose_reduction") {
      settings.loose_reduction = parse_number(value, option_field(key));
      if (!(settings.loose_reduction > 0 && settings.loose_reduction < 1))
        throw InputError(option_field(key), "= \"" + value + "\": must be between 0 and 1 (exclusive)");
    } else {
      throw InputError(option_field(key), "= \"" + value +
                                              "\": not an option of petsc; valid: method, hierarchy, p1_start, "
                                              "inexact, loose_reduction, reuse_preconditioner");
    }
  }
  return settings;
}

// K⁻¹ r = Q A⁻¹ Qᵀ r (A = QᵀKQ): the contact solve's solver of A serves certify()'s θ, so that
// the solve sets up one preconditioner in all.
//
// It also carries the solve's chain (petsc_bound_qp.hpp: A in PETSc, its hierarchy and the last
// answer) to the next solve of a QP with the same A: load steps pass the step's K_factor to the
// next step (run.hpp), whose solve then sets up nothing. `fingerprint` names that A (of_form()).
class SolverOfK final : public LinearSolver {
 public:
  SolverOfK(std::shared_ptr<const LinearSolver> of_A, std::shared_ptr<const SparseMatrix> Q,
            std::shared_ptr<BoundQpChain> chain = nullptr, std::uint64_t fingerprint = 0)
      : of_A_(std::move(of_A)), Q_(std::move(Q)), chain_(std::move(chain)), fingerprint_(fingerprint) {}
  // The chain, when it was made for a QP of this fingerprint; else null.
  std::shared_ptr<BoundQpChain> chain_for(std::uint64_t fingerprint) const {
    return chain_ && chain_->links && fingerprint == fingerprint_ ? chain_ : nullptr;
  }
  bool ok() const override { return of_A_->ok(); }
  const std::string& message() const override { return of_A_->message(); }
  int size() const override { return of_A_->size(); }
  VectorXd solve(const VectorXd& b) const override { return *Q_ * of_A_->solve(VectorXd(Q_->transpose() * b)); }
  LinearSolverStatistics statistics() const override { return of_A_->statistics(); }
  std::vector<std::string> warnings() const override { return of_A_->warnings(); }

 protected:
  std::shared_ptr<const LinearSolver> scaled_solver(double c) const override {
    // The chain stays: its A is that of the problem the backend saw (solve() scales K by the
    // same factor on the way in, and the fingerprint tells when it does not).
    return std::make_shared<SolverOfK>(of_A_->scaled(c), Q_, chain_, fingerprint_);
  }

 private:
  std::shared_ptr<const LinearSolver> of_A_;
  std::shared_ptr<const SparseMatrix> Q_;
  std::shared_ptr<BoundQpChain> chain_;
  std::uint64_t fingerprint_ = 0;
};

// What the bound form's A depends on, hashed: K, B, the friction rows and the layout (load steps
// change f, g and the friction offsets and radii, never these). One pass over K's entries, a
// small fraction of the set-up a match saves. K in rank shares: every rank must take the same
// branch, so a mismatch on any rank is a mismatch on all (collective then).
std::uint64_t of_form(const QuadraticProgram& qp, const MatrixLayout& layout) {
  std::uint64_t h = 1469598103934665603ULL;
  const auto mix = [&h](std::uint64_t word) { h = (h ^ word) * 1099511628211ULL + (h >> 29); };
  const auto mix_matrix = [&mix](const SparseMatrix& M) {
    mix(static_cast<std::uint64_t>(M.rows()));
    mix(static_cast<std::uint64_t>(M.cols()));
    for (int j = 0; j < M.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(M, j); it; ++it) {
        std::uint64_t bits;
        const double value = it.value();
        std::memcpy(&bits, &value, sizeof bits);
        mix((static_cast<std::uint64_t>(it.row()) << 32) ^ static_cast<std::uint64_t>(j));
        mix(bits);
      }
  };
  mix_matrix(qp.K);
  mix_matrix(qp.B);
  if (!qp.friction.empty()) mix_matrix(qp.friction.T);
  mix(layout.share ? 1 : 0);
  for (const int row : layout.distributed_row) mix(static_cast<std::uint64_t>(row));
  return h;
}

// The chain a solve of `qp` continues: the one options.K_factor carries, when it was made for
// the same A on every rank; else a new one.
std::shared_ptr<BoundQpChain> chain_to_continue(const SolveOptions& options, std::uint64_t fingerprint,
                                                const MatrixLayout& layout) {
  const auto* before = dynamic_cast<const SolverOfK*>(options.K_factor.get());
  std::shared_ptr<BoundQpChain> chain = before ? before->chain_for(fingerprint) : nullptr;
  if (layout.share) {
    double missing = chain ? 0 : 1;
    sum_over_ranks(&missing, 1);
    if (missing > 0) chain.reset();
  }
  return chain ? chain : std::make_shared<BoundQpChain>();
}

// The relative KKT residual of certificate.hpp without stationarity (which the inner solves
// hold): primal violation / L, negative multipliers / F, complementarity / (F L). K u sums the
// ranks' products when qp.K is a share. With friction (`lambda_t` and the discs' radii of this
// Tresca solve given) the tangential condition's natural-map residual joins, over F with
// ρ = F/L (certificate.hpp's `tangential`), and F counts Tᵀλ_T.
double relative_residual(const QuadraticProgram& qp, const MatrixLayout& layout, const VectorXd& u, const VectorXd& mu,
                         const VectorXd* lambda_t = nullptr, const VectorXd* radii = nullptr) {
  const bool friction = lambda_t && radii;
  if (mu.size() == 0 && !friction) return 0;
  const VectorXd lambda = mu.cwiseMax(0.0);
  const VectorXd w = qp.g - qp.B * u;
  VectorXd Ku = qp.K * u;
  if (layout.share) sum_over_ranks(Ku.data(), Ku.size());
  const double L = length_scale(qp, u);
  double F = force_scale(qp.f, Ku, qp.B.transpose() * lambda);
  if (friction) F = std::max(F, inf_norm(VectorXd(qp.friction.T.transpose() * *lambda_t)));
  auto ratio = [](double x, double scale) { return scale > 0 ? x / scale : x; };
  double residual = 0;
  if (mu.size() > 0) {
    const double violation = std::max(0.0, -w.minCoeff());
    const double negative = std::max(0.0, -mu.minCoeff());
    const double complementarity = lambda.cwiseProduct(w).cwiseAbs().maxCoeff();
    residual = std::max({ratio(violation, L), ratio(negative, F), ratio(complementarity, F * L)});
  }
  if (friction) {
    const double rho = F > 0 && L > 0 ? F / L : 1.0;
    const double tangential = natural_map_residual(qp.friction, *lambda_t, *radii, slip_of(qp.friction, u), rho);
    residual = std::max(residual, ratio(tangential, F));
  }
  return residual;
}

void check_petsc_options(const SolveOptions& options) { backend_settings(options); }

// What a solve of the bound form reports of itself, for the result's message.
std::string how_solved(const QuadraticProgram& qp, const BoundQpResult& solved, const SolveOptions& options) {
  return solved.method + "; " + std::to_string(solved.iterations) + " outer steps, " +
         std::to_string(solved.krylov_iterations) + " Krylov iterations" +
         (solved.preconditioner_setups > 0
              ? ", " + std::to_string(solved.preconditioner_setups) + " preconditioner set-ups"
              : std::string()) +
         "; " + std::to_string(qp.n_constraints()) + " candidate rows, " + std::to_string(solved.active) +
         " in contact" +
         (qp.friction.empty() || solved.lambda_t.size() == 0
              ? std::string()
              : " (" + std::to_string(solved.stick) + " stick, " + std::to_string(solved.slip) + " slip)") +
         (solved.multigrid.empty() ? std::string() : "; multigrid " + solved.multigrid) + "; A " +
         short_number(solved.matrix_bytes / 1048576.0) + " MiB per rank" +
         (options.verbose ? "; PETSc memory per rank " + short_number(solved.petsc_bytes / 1048576.0) +
                                " MiB (A, its working copy and the preconditioner)"
                          : std::string());
}

}  // namespace

SolveResult solve_bound_form(const QuadraticProgram& qp, const MatrixLayout& layout, const SolveOptions& options) {
  SolveResult result;
  Stopwatch clock;
  BoundQpOptions settings = backend_settings(options);
  // The kept hierarchy's solves form one chain with the solve options.K_factor comes from, when
  // that one solved the same A (a load step after the first): A stays in PETSc, its hierarchy
  // is not set up again, and the loop starts from that answer. The form is then made without A.
  const bool kept = settings.method == "pdas" && settings.kept_hierarchy;
  const std::uint64_t fingerprint = kept ? of_form(qp, layout) : 0;
  const std::shared_ptr<BoundQpChain> chain = kept ? chain_to_continue(options, fingerprint, layout) : nullptr;
  const bool continued = chain && chain->links;
  BoundForm form;
  if (!make_bound_form(qp, layout, form, result.message, !continued)) {
    result.status = Status::NumericalError;
    result.u = VectorXd::Zero(qp.n_dofs());
    result.lambda = VectorXd::Zero(qp.n_constraints());
    return result;
  }
  result.timings.add("transform", clock.seconds());

  const bool friction = form.problem.n_directions > 0;
  if (friction && !(settings.method == "pdas" && settings.kept_hierarchy))
    throw InputError("backend_options", "method=" + settings.method +
                                            (settings.kept_hierarchy ? "" : ", hierarchy=fresh") +
                                            ": the petsc backend solves friction by method=pdas with hierarchy=kept "
                                            "(the defaults) only");
  settings.tol = options.tol;
  settings.max_iterations = options.max_iterations;
  settings.petsc_options = petsc_options_of(options.library_options);
  settings.verbose = options.verbose;
  settings.residual = [&](const VectorXd& v, const VectorXd& mu) {
    return relative_residual(qp, layout, VectorXd(form.Q * v), mu);
  };
  if (options.observer)
    settings.observer = [&](int k, const VectorXd& v, const VectorXd& mu) {
      options.observer(k, VectorXd(form.Q * v), mu);
    };
  // A warm start of the wrong size is the caller's error, named before any work (as the other
  // backends name it).
  if (friction) initial_multipliers(qp, options, MultiplierSet(qp, qp.friction.threshold, true));
  BoundQpResult solved;
  std::string fixed_point_message;  // Coulomb: what the fixed point reports
  if (!friction) {
    solved = solve_bound_qp_petsc(std::move(form.problem), settings, chain.get());
    // A friction block that exerts no force (μ = 0, thresholds 0): the frictionless answer, λ_T = 0.
    if (!qp.friction.empty()) result.lambda_t = VectorXd::Zero(qp.friction.T.rows());
  } else {
    // Tresca: one solve with the QP's thresholds. Coulomb: the fixed point of Tresca solves
    // (coulomb_fixed_point.hpp), each on the same bound form with the radii μ λ_N of the one
    // before, in one chain (petsc_bound_qp.hpp): A goes into PETSc and its hierarchy is set up
    // once, and each solve starts from the last one's answer. The counts and times reported are
    // the sums over the Tresca solves.
    BoundQpResult sums;
    const auto tresca = [&](const VectorXd& radii, const SolveOptions& step_options) {
      // The form without A, then A for the chain's first solve only: the later ones find it in
      // PETSc already.
      BoundQp problem;
      {
        Eigen::SparseMatrix<double> A = std::move(form.problem.A);
        problem = form.problem;
        form.problem.A = std::move(A);
      }
      if (!chain->links) problem.A = form.problem.A;
      problem.radius = radii;
      if (step_options.initial.lambda.size() == qp.n_constraints()) {
        problem.start_lambda = step_options.initial.lambda;
        problem.start_lambda_t = step_options.initial.lambda_t;
      }
      BoundQpOptions step = settings;
      // A warm start that only gives states (a caller's, or a chain's first solve) starts the
      // loop's x at 0, and a loose first step from there would undo the states it gives: that
      // step is solved at the final rule. Along a chain the loop starts from the last answer, x
      // and states, and takes loose steps while its states change (Coulomb's later radii, a load
      // step's new loads): on mindlin-spheres.json the last step's Krylov iterations fell from
      // 1 104 to 372 (docs/friction-backends.md).
      if (problem.start_lambda.size() > 0 && !chain->links) step.inexact = false;
      step.tol = step_options.tol;
      step.friction_residual = [&](const VectorXd& v, const VectorXd& mu, const VectorXd& lambda_t) {
        return relative_residual(qp, layout, VectorXd(form.Q * v), mu, &lambda_t, &radii);
      };
      solved = solve_bound_qp_petsc(std::move(problem), step, chain.get());
      sums.krylov_iterations += solved.krylov_iterations;
      sums.linear_solves += solved.linear_solves;
      sums.preconditioner_setups += solved.preconditioner_setups;
      sums.setup_seconds += solved.setup_seconds;
      sums.pc_setup_seconds += solved.pc_setup_seconds;
      sums.iterate_seconds += solved.iterate_seconds;
      SolveResult tresca_result;
      tresca_result.status = solved.status;
      tresca_result.message = solved.status == Status::Converged
                                  ? "converged: KKT residual " + short_number(solved.residual)
                                  : solved.message;
      tresca_result.iterations = solved.iterations;
      tresca_result.lambda = solved.mu;
      tresca_result.lambda_t = solved.lambda_t;
      tresca_result.u = form.Q * solved.v;
      return tresca_result;
    };
    const SolveResult fixed_point = qp.friction.law == FrictionLaw::Coulomb
                                        ? solve_coulomb_by_fixed_point(qp, options, tresca)
                                        : tresca(form.problem.radius, options);
    result.lambda_t = solved.lambda_t;
    solved.krylov_iterations = sums.krylov_iterations;
    solved.linear_solves = sums.linear_solves;
    solved.preconditioner_setups = sums.preconditioner_setups;
    solved.setup_seconds = sums.setup_seconds;
    solved.pc_setup_seconds = sums.pc_setup_seconds;
    solved.iterate_seconds = sums.iterate_seconds;
    for (const auto& [name, value] : fixed_point.diagnostics) result.diagnostics[name] = value;
    if (qp.friction.law == FrictionLaw::Coulomb) {
      solved.status = fixed_point.status;
      solved.iterations = fixed_point.iterations;
      fixed_point_message = fixed_point.message;
      if (fixed_point.status != Status::Converged) solved.message = fixed_point.message;
    }
    result.diagnostics["stick_nodes"] = static_cast<double>(solved.stick);
    result.diagnostics["slip_nodes"] = static_cast<double>(solved.slip);
  }
  // factorize: the matrix into PETSc and the preconditioner's set-up (the kept hierarchy's, or
  // none when every step sets up its own inside the loop); iterate and solve: the loop.
  result.timings.add("factorize", solved.setup_seconds + solved.pc_setup_seconds);
  result.timings.add("iterate", solved.iterate_seconds - solved.pc_setup_seconds);
  result.timings.add("solve", solved.iterate_seconds - solved.pc_setup_seconds);

  result.u = form.Q * solved.v;
  result.lambda = solved.mu;
  result.iterations = solved.iterations;
  result.warnings = solved.warnings;
  result.diagnostics["outer_iterations"] = solved.iterations;
  result.diagnostics["krylov_iterations"] = static_cast<double>(solved.krylov_iterations);
  result.diagnostics["linear_solves"] = static_cast<double>(solved.linear_solves);
  if (solved.preconditioner_setups > 0) result.diagnostics["preconditioner_setups"] = solved.preconditioner_setups;
  if (solved.solver_of_A) {
    result.diagnostics["preconditioner_setup_seconds"] = solved.pc_setup_seconds;
    result.diagnostics["p1_start_steps"] = solved.p1_steps;
    result.diagnostics["p1_start_krylov_iterations"] = static_cast<double>(solved.p1_krylov_iterations);
  }
  result.diagnostics["active_constraints"] = solved.active;
  result.diagnostics["kkt_residual"] = solved.residual;
  result.diagnostics["petsc_matrix_mb_per_rank"] = solved.matrix_bytes / 1048576.0;
  result.diagnostics["petsc_memory_mb_per_rank"] = solved.petsc_bytes / 1048576.0;
  // What this rank assembled: the whole K, or under mpirun its share (qp.hpp); rank 0's in the
  // result files.
  result.diagnostics["k_rank_share"] = layout.share ? 1 : 0;
  result.diagnostics["k_nonzeros_this_rank"] = static_cast<double>(qp.K.nonZeros());

  const std::string how = how_solved(qp, solved, options);
  result.status = solved.status;
  result.message = !fixed_point_message.empty()         ? fixed_point_message + " (" + how + ")"
                   : solved.status == Status::Converged ? "converged: KKT residual " + short_number(solved.residual) +
                                                              " <= " + short_number(options.tol) + " (" + how + ")"
                                                        : solved.message + " (" + how + ")";

  // A PETSc solver of K for certify() (θ needs one solve), so that no rank factorises K: the
  // factor is what the petsc backend is there to avoid.
  if (options.K_factor) {
    result.K_factor = options.K_factor;
  } else if (solved.solver_of_A && solved.solver_of_A->ok()) {
    result.K_factor = std::make_shared<SolverOfK>(
        solved.solver_of_A, std::make_shared<const SparseMatrix>(std::move(form.Q)), chain, fingerprint);
  } else {
    LinearSolverOptions settings_of_K = linear_solver_options(qp, options);
    settings_of_K.kind = LinearSolverKind::Petsc;
    Stopwatch factor_clock;
    result.K_factor = make_petsc_solver(qp.K, settings_of_K, layout);
    result.timings.add("factorize", factor_clock.seconds());
    if (!result.K_factor->ok()) result.K_factor.reset();  // certify() then reports θ unavailable
  }
  return result;
}

}  // namespace contactqp::detail

CONTACTQP_BUILTIN(petsc) {
  BackendRegistration petsc;
  petsc.name = "petsc";
  petsc.summary = "the bound form solved by PETSc (active set with KSP solves, or TAO), under mpirun too";
  petsc.order = 60;
  petsc.option_names = {"method", "hierarchy", "p1_start", "inexact", "loose_reduction", "reuse_preconditioner"};
  petsc.check_options = check_petsc_options;
  petsc.problem_kinds = {ProblemKind::Frictionless, ProblemKind::Tresca, ProblemKind::Coulomb};
  petsc.max_friction_directions = 2;  // 2D and 3D (bound_pdas.cpp's tangential states)
#ifdef CONTACTQP_HAVE_PETSC           // set by CMake when PETSc was found (CONTACTQP_WITH_PETSC)
  petsc.solve = [](const QuadraticProgram& qp, const SolveOptions& options) {
    return solve_bound_form(qp, MatrixLayout{}, options);  // K whole on every rank
  };
#else
  petsc.available = false;
#endif
  register_backend(petsc);
}
