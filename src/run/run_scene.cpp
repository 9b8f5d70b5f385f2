// run_scene(): one scene from model to post-processed report (run.hpp).
#include <algorithm>

#include "contactqp/certificate.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/estimate.hpp"
#include "contactqp/phases.hpp"
#include "contactqp/run.hpp"
#include "contactqp/solve.hpp"
#include "run/adaptive_run.hpp"
#include "run/distributed_run.hpp"
#include "run/load_steps.hpp"
#include "run/problem_in_parts.hpp"

namespace contactqp {
namespace {

// The strain energy and, unless the scene turns it off, the error estimate (docs/estimate.md),
// timed as the phase "estimate".
void add_error_estimate(const Scene& scene, const Model& model, const QuadraticProgram& qp, RunReport& report) {
  if (report.result.u.size() != qp.n_dofs()) return;  // no displacement to estimate (a failed solve)
  Stopwatch clock;
  if (scene.estimate) {
    report.error_estimate =
        estimate_error(model, qp, report.result.u, report.no_contact ? Eigen::VectorXd() : report.result.lambda,
                       report.friction ? &*report.friction : nullptr);
    report.strain_energy = report.error_estimate->strain_energy;
  } else {
    report.strain_energy = strain_energy(model, report.result.u);
  }
  report.timings.add("estimate", clock.seconds());
}

// The scene's solver options with the caller's start (RunOptions::initial_guess), if any.
SolveOptions with_initial_guess(const SolveOptions& solver, const RunOptions& options, const Model& model,
                                const QuadraticProgram& qp) {
  SolveOptions with = solver;
  if (options.initial_guess) with.initial = options.initial_guess(model, qp);
  return with;
}

}  // namespace

RunReport run_scene(const Scene& scene, const RunOptions& options) {
  // Cycles of this function on meshes the error estimate chooses (docs/adaptive.md).
  if (scene.adapt) return detail::run_adaptive(scene, options);
  // Under mpirun the petsc backend's run is distributed: no process holds the whole mesh.
  if (runs_distributed(scene, options)) return detail::run_scene_distributed(scene, options);
  Stopwatch total;
  validate_options(scene.solver);  // backend options too, before the mesh is built
  const auto phase = [&options](const char* name) {
    begin_phase(name);  // where the processes of a run under mpirun agree that none failed
    if (options.on_phase) options.on_phase(name);
  };

  phase("mesh");
  auto model = std::make_shared<Model>(build_model(scene, options.build));
  if (options.no_contact && model->free_modes.cols() > 0)
    throw InputError("--no-contact", "the body is held only by its contacts (it moves freely " +
                                         describe_free_motion(*model, model->free_modes.col(0)) +
                                         " without them): without contact K is singular and nothing holds the load");
  phase("assemble");
  // On several processes a backend that solves a problem held in parts takes it so (the petsc
  // backend under mpirun, docs/petsc.md): no process then holds the whole K. Every other solve
  // needs K whole.
  const std::shared_ptr<detail::ProblemInParts> in_parts =
      options.no_contact ? nullptr : detail::assemble_in_parts(*model, scene.solver);
  // The whole QP, which load steps change step by step (loads, gaps, friction offset).
  const std::shared_ptr<QuadraticProgram> whole =
      in_parts ? nullptr : std::make_shared<QuadraticProgram>(assemble_qp(*model));
  const std::shared_ptr<const QuadraticProgram> qp =
      in_parts ? std::shared_ptr<const QuadraticProgram>(in_parts, &in_parts->part()) : whole;

  RunReport report;
  report.model = model;
  report.qp = qp;
  report.size = {model->mesh.n_nodes(), model->mesh.n_elements(), qp->n_dofs(), qp->n_constraints()};
  report.options = scene.solver;
  report.options.observer = nullptr;  // a callback is not data: the report must not keep the caller's closure alive
  report.no_contact = options.no_contact;
  phase("solve");
  if (options.no_contact)
    report.result = solve_without_contact(*qp, scene.solver);
  else if (in_parts && scene.steps.empty())  // the start reads the model and B, whole on every rank
    report.result = in_parts->solve(with_initial_guess(scene.solver, options, *model, *qp));
  else if (in_parts)  // each step changes the part's f, g and friction offset, not its K
    report.result = detail::solve_load_steps_with(
        *model, in_parts->part_to_step(), scene, report.options, &report.steps,
        [&in_parts](const SolveOptions& step_options) { return in_parts->solve(step_options); });
  else if (scene.steps.empty())
    report.result = solve(*qp, with_initial_guess(scene.solver, options, *model, *qp));
  else
    report.result = solve_load_steps(*model, *whole, scene, report.options, &report.steps);

  // A body only its contacts hold, which the load pulls away from them: name the motion.
  if (report.result.status == Status::Unbounded && report.result.recession.size() == model->n_free &&
      model->free_modes.cols() > 0) {
    const std::string prefix = "unbounded: ", slip = "unbounded: gross slip: ";
    const std::string& said = report.result.message;
    const Eigen::VectorXd& d = report.result.recession;
    if (said.compare(0, slip.size(), slip) == 0)  // a tangential load beyond what friction holds
      report.result.message = slip + describe_free_motion(*model, d, "slides") + ": " + said.substr(slip.size());
    else
      report.result.message = prefix + describe_free_motion(*model, d, "moves freely") +
                              ": the load pushes it away from every contact (" +
                              (said.compare(0, prefix.size(), prefix) == 0 ? said.substr(prefix.size()) : said) + ")";
  }

  phase("certify");
  Stopwatch clock;
  // solve() certified its answer (its timings hold "certify"); a solve without contact did not.
  const bool certified = report.result.certificate.has_value();
  if (certified)
    report.certificate = *report.result.certificate;
  else
    report.certificate = in_parts ? in_parts->certify(report.result.u, report.result.lambda, report.result.lambda_t,
                                                      report.result.K_factor.get())
                                  : certify(*qp, report.result.u, report.result.lambda, report.result.lambda_t,
                                            report.result.K_factor.get());
  report.timings.merge(model->timings);
  report.timings.merge(report.result.timings);
  if (!certified) report.timings.add("certify", clock.seconds());
  phase("postprocess");
  clock.restart();
  PostProcessed state = postprocess(*model, *qp, report.result);
  report.contact = std::move(state.contact);
  // With several bodies the obstacles' Hertz would need each body's material: the pairs have theirs.
  if (!report.no_contact && model->bodies.empty()) {
    report.hertz = compare_with_hertz(*model, report.contact);
    report.boussinesq = compare_with_boussinesq(*model, report.contact);
  }
  report.reactions = std::move(state.reactions);
  // No equilibrium (unbounded, infeasible) leaves nothing whose mean motion means anything.
  if (report.result.status != Status::Unbounded && report.result.status != Status::Infeasible)
    report.floating = floating_bodies(*model, report.result.u);
  report.pairs = std::move(state.pairs);
  report.friction = std::move(state.friction);
  // The largest contact pressure anywhere, as the VTU's contact_pressure field holds it: the
  // pairs' nodal pressures on both sides too.
  for (const PairContact& pair : report.pairs)
    report.contact.max_pressure =
        std::max({report.contact.max_pressure, pair.max_nodal_pressure, pair.face_max_pressure});
  report.timings.add("postprocess", clock.seconds());
  // From the model, u, λ, B, g and T: whole on every rank of a problem in parts too.
  add_error_estimate(scene, *model, *qp, report);

  report.warnings = model->warnings;
  report.warnings.insert(report.warnings.end(), report.result.warnings.begin(), report.result.warnings.end());
  if (report.contact.penetrating_non_candidates > 0 && !report.no_contact)
    report.warnings.push_back(std::to_string(report.contact.penetrating_non_candidates) +
                              " boundary nodes outside the candidate set penetrate an obstacle (by up to " +
                              format_value(report.contact.max_non_candidate_penetration) + "); raise contact.max_gap");
  for (const PairContact& pair : report.pairs)
    if (pair.slipped_nodes > 0 && !report.no_contact)
      report.warnings.push_back(std::to_string(pair.slipped_nodes) + " loaded nodes of " + pair.node_side +
                                " slid off the faces of " + pair.face_side +
                                " their rows were linearised on (tangential slip up to " + format_value(pair.max_slip) +
                                "); the small-slip rows are then inexact: refine, or shorten the load step");
  // "total" is the whole run: the backend's own total stays under its name in the registry.
  Timings timings;
  for (const auto& [phase, seconds] : report.timings.phases())
    if (phase != "total") timings.add(phase, seconds);
  timings.add("total", total.seconds());
  report.timings = timings;
  return report;
}

RunReport run_scene(const std::string& scene_path, const RunOptions& options) {
  return run_scene(load_scene(scene_path), options);
}

}  // namespace contactqp
