// run_scene() with each process holding only its part of everything that grows with the mesh
// (docs/petsc-design.md, "Distributed runs"): the mesh, the model, A = QᵀKQ, the vectors and the
// ParaView output; load steps along the path on the same A and hierarchy. Taken for the petsc
// backend under mpirun (or with RunOptions::distributed);
// the report is run_scene()'s, the summary and the result files on rank 0, and every rank writes
// its piece of the .pvtu through RunReport::write_pieces. Registered with run_scene() at the end.
#include <mpi.h>

#include <algorithm>
#include <functional>
#include <sstream>

#include "backend_options.hpp"
#include "contactqp/backend.hpp"
#include "contactqp/certificate.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/linear_solver.hpp"
#include "contactqp/number_format.hpp"
#include "contactqp/phases.hpp"
#include "contactqp/processes.hpp"
#include "contactqp/solve.hpp"
#include "distributed_estimate.hpp"
#include "distributed_post.hpp"
#include "fe/stiffness_matrix.hpp"
#include "model/model_parts.hpp"
#include "mpi.hpp"
#include "run_distributed.hpp"

namespace contactqp::detail {
namespace {

// The petsc backend's options (petsc_backend.cpp reads and checks the same keys; they were
// validated before this runs): unaddressed keys and "petsc.key". A distributed run solves by the
// kept hierarchy's pdas (hierarchy=kept), with the P1 start for quadratic elements unless
// p1_start=false.
DistributedPdasOptions pdas_options(const SolveOptions& options) {
  DistributedPdasOptions out;
  out.tol = options.tol;
  out.max_iterations = options.max_iterations;
  out.petsc_options = petsc_options_of(options.library_options);
  for (const auto& [key, value] : options_for(Backend::Petsc, options.backend_options)) {
    if (key == "inexact") out.inexact = value == "true" || value == "1";
    if (key == "p1_start") out.p1_start = value == "true" || value == "1";
    if (key == "loose_reduction") out.loose_reduction = parse_number(value, option_field(key));
    if (key == "method" && value != "pdas")
      throw InputError("backend option method", "= \"" + value + "\": a distributed run (mpirun) solves by pdas only");
    if (key == "hierarchy" && value != "kept")
      throw InputError("backend option hierarchy",
                       "= \"" + value + "\": a distributed run (mpirun) keeps one hierarchy (hierarchy=kept)");
  }
  return out;
}

SolveResult solve_result(const DistributedPdasResult& solved, const DistributedModel& model, double tol, bool verbose) {
  SolveResult result;
  result.status = solved.status;
  result.iterations = solved.iterations;
  result.warnings = solved.warnings;
  result.timings.add("factorize", solved.setup_seconds);
  result.timings.add("iterate", solved.iterate_seconds);
  result.timings.add("solve", solved.iterate_seconds);
  auto& d = result.diagnostics;
  d["outer_iterations"] = solved.iterations;
  d["krylov_iterations"] = static_cast<double>(solved.krylov_iterations);
  d["linear_solves"] = static_cast<double>(solved.linear_solves);
  if (solved.preconditioner_setups > 0) d["preconditioner_setups"] = solved.preconditioner_setups;
  d["active_constraints"] = static_cast<double>(solved.active);
  d["kkt_residual"] = solved.residual;
  d["petsc_matrix_mb_per_rank"] = solved.matrix_bytes / 1048576.0;
  d["petsc_memory_mb_per_rank"] = solved.petsc_bytes / 1048576.0;
  if (solved.multigrid_levels > 0) {
    d["multigrid_levels"] = solved.multigrid_levels;
    d["grid_complexity"] = solved.grid_complexity;
    d["operator_complexity"] = solved.operator_complexity;
  }
  d["distributed"] = 1;
  d["ranks"] = process_count();
  d["dofs_this_rank"] = model.n_own_dofs;
  std::ostringstream levels;
  levels.precision(3);
  if (solved.multigrid_levels > 0)
    levels << "; multigrid " << solved.multigrid_levels << " levels, grid complexity " << solved.grid_complexity
           << ", operator complexity " << solved.operator_complexity;
  const std::string multigrid = levels.str();
  const std::string how = solved.method + "; " + std::to_string(solved.iterations) + " outer steps, " +
                          std::to_string(solved.krylov_iterations) + " Krylov iterations" +
                          (solved.preconditioner_setups > 0
                               ? ", " + std::to_string(solved.preconditioner_setups) + " preconditioner set-ups"
                               : std::string()) +
                          "; " + std::to_string(model.n_global_candidates) + " candidate rows, " +
                          std::to_string(solved.active) + " in contact" + multigrid + "; A " +
                          short_number(solved.matrix_bytes / 1048576.0) + " MiB per rank" +
                          (verbose ? "; PETSc memory per rank " + short_number(solved.petsc_bytes / 1048576.0) +
                                         " MiB (A, its working copy and the preconditioner)"
                                   : std::string());
  result.message = solved.status == Status::Converged ? "converged: KKT residual " + short_number(solved.residual) +
                                                            " <= " + short_number(tol) + " (" + how + ")"
                                                      : solved.message + " (" + how + ")";
  return result;
}

// One solve of the QP as it stands, certified: the status claims no more than the certificate
// shows.
struct CertifiedSolve {
  DistributedPdasResult solved;
  SolveResult result;
  Certificate certificate;
  DistributedSolution solution;
};

using Phase = std::function<void(const char* name)>;

// `previous`: the load step before, whose hierarchy and answer this one starts from. `phase`
// is called with "certify" between the solve and its certificate.
CertifiedSolve solve_and_certify(const DistributedModel& model, const DistributedBoundQp& qp,
                                 const DistributedPdasOptions& settings, bool verbose,
                                 const DistributedPdasResult* previous, const Phase& phase) {
  CertifiedSolve out;
  DistributedPdasOptions solve_settings = settings;
  solve_settings.residual = [&](Vec v, const std::vector<double>& mu) {
    return distributed_kkt_residual(model, qp, v, mu);
  };
  out.solved = solve_distributed_pdas(qp, solve_settings, previous);
  out.result = solve_result(out.solved, model, settings.tol, verbose);
  out.solution = solution_of(model, qp, out.solved.v, out.solved.mu);
  phase("certify");
  Stopwatch clock;
  out.certificate = certificate_from(
      distributed_certificate_terms(model, qp, out.solution, out.solved.solver_of_A.get(), settings.tol));
  // Without contact the certificate shows the penetration (as a one-process --no-contact run's
  // does) and says nothing of the linear solve's status.
  if (!settings.without_bounds) apply_certificate(out.result, out.certificate, settings.tol);
  out.result.timings.add("certify", clock.seconds());
  return out;
}

// What the summary and the result files say of a solution: the contact (on rank 0), the
// reactions, and what this rank's ParaView piece needs. Collective.
struct DistributedState {
  std::shared_ptr<Eigen::VectorXd> local_u, own_lambda;
  std::shared_ptr<std::vector<double>> own_pressure = std::make_shared<std::vector<double>>();
  ContactSurface surface;
  ContactSummary contact;
  std::vector<Reaction> reactions;
};

DistributedState state_of(const DistributedModel& model, const DistributedSolution& solution) {
  DistributedState state;
  state.local_u = std::make_shared<Eigen::VectorXd>(local_free_values(model, solution.u));
  state.own_lambda = std::make_shared<Eigen::VectorXd>(solution.lambda);
  const Eigen::VectorXd displacement = full_displacement(model.local, *state.local_u);
  state.surface = gather_contact_surface(model, solution.lambda);
  state.contact = distributed_contact_summary(model, state.surface, displacement, *state.own_pressure);
  state.reactions = distributed_reactions(model, *state.local_u, solution.lambda);
  return state;
}

// The load path (docs/petsc-design.md, "Load steps on the distributed run"), frictionless: each step
// sets the loads' shares scaled by its factors, then f, b and the bounds (A and its hierarchy
// stay: the first step sets the hierarchy up, every later one starts from the answer before
// it). Each step is certified within the solve phase. Ends at the first step that does not
// converge, as the one-process path does. Collective.
CertifiedSolve solve_load_steps(const Scene& scene, DistributedModel& model, DistributedBoundQp& qp,
                                const DistributedPdasOptions& settings, RunReport& report) {
  const std::vector<std::vector<double>> factors = load_factors(scene);
  CertifiedSolve last;
  Timings timings;
  int iterations = 0;
  for (std::size_t k = 0; k < factors.size(); ++k) {
    const std::string& path = scene.steps[k].path;
    set_step_loads(model.local, factors[k], path);
    checkpoint();  // a conflict between two loads is found by the ranks that hold the node
    const LoadVectorRange f = set_load_vectors(model, qp);
    refuse_unrepresentable(model.local, 1.0, true, f.largest, f.finite);  // K was checked at assembly
    Stopwatch clock;
    CertifiedSolve step = solve_and_certify(model, qp, settings, scene.solver.verbose, k > 0 ? &last.solved : nullptr,
                                            [](const char*) {});
    StepReport out;
    out.seconds = clock.seconds();
    out.path = path;
    for (std::size_t l = 0; l < model.local.scene.loads.size(); ++l)
      if (!model.local.scene.loads[l].name.empty())
        out.factors.emplace_back(model.local.scene.loads[l].name, factors[k][l]);
    out.status = step.result.status;
    out.message = step.result.message;
    out.iterations = step.result.iterations;
    out.diagnostics = step.result.diagnostics;
    // Where the step's time went: the hierarchy's set-up (the first step's), the loop, the certificate.
    for (const auto& [name, seconds] : step.result.timings.phases()) out.diagnostics[name + "_seconds"] = seconds;
    DistributedState state = state_of(model, step.solution);
    out.contact = std::move(state.contact);
    out.reactions = std::move(state.reactions);
    report.steps.push_back(std::move(out));
    timings.merge(step.result.timings);
    iterations += step.result.iterations;
    last = std::move(step);
    if (last.result.status != Status::Converged) break;  // a later step would start from a wrong state
  }
  last.result.timings = timings;
  last.result.iterations = iterations;
  return last;
}

}  // namespace

// Collective. What run_scene() does, distributed (run_distributed.hpp).
RunReport run_distributed(const Scene& scene, const RunOptions& options) {
  Stopwatch total;
  validate_options(scene.solver);
  // What the distributed path does not model yet, refused as the one-process path refuses it.
  for (const LoadSpec& load : scene.loads)
    if (load.is<RigidForceLoad>())
      throw InputError(load.path + ".type",
                       "= \"force\": a distributed run (mpirun) does not model a rigid surface "
                       "yet; run it on one process");
  if (scene.friction_law() != FrictionLaw::None)
    throw InputError("backend", "= \"petsc\": " + to_string(scene.friction_law()) +
                                    " friction is not solved on several processes (under mpirun) yet: run the "
                                    "scene on one process (petsc solves friction there), or with another backend");
  DistributedPdasOptions settings = pdas_options(scene.solver);
  settings.without_bounds = options.no_contact;
  const auto phase = [&options](const char* name) {
    begin_phase(name);  // where the ranks agree that none failed (run/phases.hpp)
    if (options.on_phase) options.on_phase(name);
  };

  // PETSc, with the user's options on its command line: after an agreement that no rank has
  // failed, since starting it is collective (a rank that failed before would leave the others
  // waiting in it), and before the phase's own failures, which the others then meet at the
  // mesh's first checkpoint instead of inside PETSc's start.
  checkpoint();
  start_process_runtime(scene.solver.library_options);
  phase("mesh");
  auto model = std::make_shared<DistributedModel>(build_distributed_model(scene, options.build, phase));
  RunReport report;
  report.options = scene.solver;
  report.options.observer = nullptr;
  report.timings.merge(model->local.timings);
  report.size = {model->n_global_nodes, model->n_global_elements, model->n_global_dofs, model->n_global_candidates};
  report.no_contact = options.no_contact;

  DistributedSolution solution;
  {
    phase("assemble");
    Stopwatch clock;
    DistributedBoundQp qp = assemble_distributed_bound_qp(*model);
    report.timings.add("assemble", clock.seconds());

    phase("solve");
    // Without contact the loads in full, as the one-process path solves them.
    CertifiedSolve solved = scene.steps.empty() || options.no_contact
                                ? solve_and_certify(*model, qp, settings, scene.solver.verbose, nullptr, phase)
                                : solve_load_steps(scene, *model, qp, settings, report);
    report.result = std::move(solved.result);
    report.certificate = solved.certificate;
    report.timings.merge(report.result.timings);
    solution = std::move(solved.solution);
  }  // A, its preconditioner and the PETSc vectors are freed here, before the output is made

  phase("postprocess");
  Stopwatch clock;
  DistributedState state = state_of(*model, solution);
  report.contact = std::move(state.contact);
  const ContactSurface& surface = state.surface;
  if (surface.model) {
    if (!options.no_contact) {
      report.hertz = compare_with_hertz(*surface.model, report.contact);
      report.boussinesq = compare_with_boussinesq(*surface.model, report.contact);
    }
    report.model = surface.model;
    report.qp = surface.qp;
    report.result.lambda = surface.lambda;
  } else {
    auto shape = std::make_shared<Model>();
    shape->scene = model->local.scene;
    shape->dim = model->local.dim;
    shape->mesh.dim = model->local.mesh.dim;
    shape->mesh.order = model->local.mesh.order;
    report.model = shape;
    report.qp = std::make_shared<QuadraticProgram>();
  }
  report.reactions = std::move(state.reactions);
  report.timings.add("postprocess", clock.seconds());
  // The strain energy and, unless the scene turns it off, the error estimate (docs/estimate.md),
  // each rank on its part: as the one-process run adds them after the post-processing.
  clock.restart();
  auto indicator = std::make_shared<Eigen::VectorXd>();
  if (scene.estimate) {
    report.error_estimate =
        distributed_error_estimate(*model, *state.local_u, *state.own_pressure, !options.no_contact);
    report.strain_energy = report.error_estimate->strain_energy;
    *indicator = report.error_estimate->indicator;
  } else {
    report.strain_energy = distributed_strain_energy(*model, *state.local_u);
  }
  report.timings.add("estimate", clock.seconds());

  report.warnings = model->local.warnings;
  report.warnings.insert(report.warnings.end(), report.result.warnings.begin(), report.result.warnings.end());
  if (report.contact.penetrating_non_candidates > 0 && !options.no_contact)
    report.warnings.push_back(std::to_string(report.contact.penetrating_non_candidates) +
                              " boundary nodes outside the candidate set penetrate an obstacle (by up to " +
                              format_value(report.contact.max_non_candidate_penetration) + "); raise contact.max_gap");
  report.write_pieces = [model, local_u = state.local_u, own_lambda = state.own_lambda,
                         own_pressure = state.own_pressure, indicator](const std::string& path) {
    const Eigen::VectorXd moved = full_displacement(model->local, *local_u);
    const PieceArrays piece = piece_arrays(*model, moved, *local_u, *own_lambda, *own_pressure);
    std::vector<PointArray> cells;
    if (indicator->size() == model->local.mesh.n_elements())
      cells.push_back({"error_indicator", 1, indicator->data(), {}});
    write_pvtu(path, model->local.mesh, piece.arrays(), cells);
  };
  Timings timings;
  for (const auto& [name, seconds] : report.timings.phases())
    if (name != "total") timings.add(name, seconds);
  timings.add("total", total.seconds());
  report.timings = timings;
  return report;
}

}  // namespace contactqp::detail
