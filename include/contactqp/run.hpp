// The whole run as one call (docs/architecture.md, "The flow of data"):
//
//     scene ──► build_model ──► assemble_qp ──► solve ──► certify ──► post-process ──► report
//
// run_scene() is what `contactqp solve` does and compare_scene() what `contactqp compare` does;
// the command-line tool, the Python module and the benchmarks call these and only print, write
// or wrap the report. A report owns everything it holds (the model and the QP through shared,
// read-only pointers), so it stays valid after the scene and the options are gone.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "contactqp/certificate.hpp"
#include "contactqp/io.hpp"
#include "contactqp/model.hpp"
#include "contactqp/post.hpp"
#include "contactqp/qp.hpp"
#include "contactqp/scene.hpp"

namespace contactqp {

// How one scene is run. The solver settings are the scene's own `solver` section
// (Scene::solver): override them there before the call.
struct RunOptions {
  BuildOptions build;       // mesh limits (max_elements)
  bool no_contact = false;  // drop the contact rows: one linear solve of the same K (the unit of cost)
  // Each process holds only its part of the mesh, the model and the output (docs/petsc.md,
  // "Distributed runs"). The petsc backend under mpirun does so anyway; true asks for it on one
  // process too, where that path models the scene (one body, frictionless, no load steps; then
  // "model" is a phase of its own, after "mesh"). `contactqp solve` sets it. False keeps the
  // report whole on one process: result.u, the model and the QP, which a distributed run's
  // report does not hold (it holds the contact surface gathered).
  bool distributed = false;
  // Under mpirun, hold the mesh and the model whole on every process even where the distributed
  // run models the scene: the petsc backend then solves the problem in parts (K in rank shares),
  // and the report holds u, the model and the QP whole on every process. An adaptive run
  // (docs/adaptive.md) plans each next mesh from them. Takes precedence over `distributed`.
  bool whole = false;
  // Called as each phase starts: "mesh" (with the model), "assemble", "solve", "certify",
  // "postprocess". For a progress display; empty: not called.
  std::function<void(const char* phase)> on_phase;
  // Called once the QP is assembled, before a solve without load steps: the backend's start
  // (SolveOptions::initial) for the model just built. Empty: each backend's own. An adaptive run
  // (docs/adaptive.md) carries each cycle's answer to the next mesh with it.
  std::function<InitialGuess(const Model& model, const QuadraticProgram& qp)> initial_guess;
};

// Validates the solver options (InputError naming the field, before any work), builds the
// model, assembles and solves the QP, certifies the answer with the backend's factor of K,
// and post-processes it (contact summary, Hertz comparison, reactions). RunReport::timings
// holds every phase — mesh, assemble, factorize, solve, ..., certify, postprocess — and
// "total", the wall time of the whole call. RunReport::warnings lists the model's warnings
// and penetrating non-candidates; nothing is printed. The observer in scene.solver is called
// during the solve and is not kept in the report.
RunReport run_scene(const Scene& scene, const RunOptions& options = {});
// The same for a scene file (InputError("path", ...) when it cannot be read).
RunReport run_scene(const std::string& scene_path, const RunOptions& options = {});

// Whether run_scene() takes the distributed path for this scene with these options (under
// mpirun, or options.distributed on one process; false when contactqp was built without
// PETSc): such a run writes its ParaView file in pieces, one per process, joined by a .pvtu.
bool runs_distributed(const Scene& scene, const RunOptions& options);

// The contact a solution gives: the summary over the obstacles, each pair's, the supports'
// reactions and, with friction, each row's friction (FrictionZone in the summaries too).
struct PostProcessed {
  ContactSummary contact;
  std::vector<PairContact> pairs;
  std::vector<Reaction> reactions;
  std::optional<FrictionFields> friction;
};
PostProcessed postprocess(const Model& model, const QuadraticProgram& qp, const SolveResult& result);

// Solves a scene's load steps (scene.steps, docs/friction.md) in order on its model and QP: each
// step sets its loads (apply_load_step) and the friction offset (the last step's tangential
// positions), reuses the last step's factor of K and starts from its solution, and is
// post-processed into `steps` (when given). Stops after a step that did not converge. Returns
// the last step's result; the model and the QP are left at the last step solved.
SolveResult solve_load_steps(Model& model, QuadraticProgram& qp, const Scene& scene, const SolveOptions& options,
                             std::vector<StepReport>* steps = nullptr);

// How closely converged backends must agree at tolerance T for a comparison to pass. Each
// backend stops when its relative KKT residuals are below T; the error of a solution is that
// residual amplified by the conditioning of the contact problem, more so for λ (a force read
// off B K⁻¹ Bᵀ) than for u. The factors leave room for that on the shipped scenes and still
// catch a wrong answer, which differs at the percent level.
struct Agreement {
  double u = 0, lambda = 0, gap = 0;  // bounds on ‖u_a − u_b‖/max‖u‖, ‖λ_a − λ_b‖/max‖λ‖, |relative gap|
};
Agreement agreement_for(double tol);  // {1e4 T, 1e5 T, 1e2 T}

struct CompareOptions {
  BuildOptions build;
  // In this order; empty: available_backends(qp), those that solve the scene's problem (its kind
  // and, with friction, its dimension). A listed backend that does not is an InputError before any solve.
  std::vector<Backend> backends;
};

// One backend's run within a comparison.
struct BackendRun {
  Backend backend = Backend::Uzawa;
  SolveResult result;       // its K_factor released: a factor per backend is memory the next one may need
  Certificate certificate;  // computed with the comparison's own factor of K, the same for every run
  ContactSummary contact;
  // ‖x − x_ref‖/‖x_ref‖ against the reference run; with friction λ stands for (λ_N, λ_T)
  std::optional<double> rel_diff_u, rel_diff_lambda;
};

struct CompareReport {
  std::shared_ptr<const Model> model;
  std::shared_ptr<const QuadraticProgram> qp;
  double tol = 0;                // every backend's tolerance T (the scene's solver.tol)
  std::vector<BackendRun> runs;  // in CompareOptions::backends order
  int reference = -1;            // the converged run with the smallest certified |gap|; −1 when none has θ
  Agreement bound;               // agreement_for(tol)
  double max_diff_u = 0, max_diff_lambda = 0, max_gap = 0;  // pairwise maxima, symmetric relative 2-norms
  bool all_converged = false;                               // every run converged and has a dual objective
  bool agree = false;                                       // all_converged and every maximum within its bound
  // One factorisation of K and the fastest of five solves with it: the unit of cost
  // (docs/architecture.md, "Where the time goes"); linear_solve_seconds is NaN when K cannot
  // be factorised.
  double factorize_seconds = 0, linear_solve_seconds = 0;
  Timings timings;                    // "mesh", "assemble" (the model's) and "total" (the whole call)
  std::vector<std::string> warnings;  // the model's
};

// Solves the scene's QP with each backend from scratch (its own factorisation included, so
// that times compare), certifies every run with one shared factor, and measures how far the
// answers lie from each other. A scene with load steps: each backend runs the whole path
// (solve_load_steps) and the last steps are compared. Every backend's options are validated
// before any work.
CompareReport compare_scene(const Scene& scene, const CompareOptions& options = {});
CompareReport compare_scene(const std::string& scene_path, const CompareOptions& options = {});

// The comparison as the JSON `contactqp compare --json` writes (docs/cli.md).
std::string compare_json(const CompareReport& report);

}  // namespace contactqp
