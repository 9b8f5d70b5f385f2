// run_adaptive(): a scene with "adapt" solved on meshes the error estimate chooses
// (docs/adaptive.md): solve, estimate, plan the sizes of the next mesh from the indicators
// (adaptive_sizes.hpp), remesh the generated bodies with Gmsh, solve again.
#include <cmath>
#include <memory>

#include "adaptive_sizes.hpp"
#include "adaptive_warm_start.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/number_format.hpp"
#include "contactqp/run.hpp"
#include "run/adaptive_run.hpp"

namespace contactqp::detail {
namespace {

// The next mesh aims below the target by this factor: the error model is rough, and a mesh
// that just misses costs a whole cycle more.
constexpr double kAim = 0.8;
// A cycle at most quadruples the elements (in 3D too: its sizes change by at most 2 per cycle,
// adaptive_sizes.cpp), so that a wrong guess of where the error lives costs little.
constexpr double kMaxGrowth = 4;

std::vector<BodySpec*> scene_bodies(Scene& scene) {
  std::vector<BodySpec*> bodies;
  if (scene.bodies.empty())
    bodies.push_back(&scene.body);
  else
    for (SceneBody& body : scene.bodies) bodies.push_back(&body.body);
  return bodies;
}

std::string percent(double fraction) { return number(100 * fraction, 3) + "%"; }

void check_adaptive_scene(Scene& scene) {
  const AdaptSpec& spec = *scene.adapt;
  if (!scene.estimate) throw InputError("estimate", "= false: an adaptive run (\"adapt\") needs the error estimate");
  bool generated = false;
  for (const BodySpec* body : scene_bodies(scene)) generated = generated || body->shape != "mesh";
  if (!generated)
    throw InputError("adapt",
                     "needs a generated body (half_disc, rectangle, hemisphere or box) to remesh: the scene's "
                     "bodies are mesh files, which an adaptive run cannot remesh");
  require(spec.target > 0 && spec.target < 1, "adapt.target", spec.target, "must lie in (0, 1)");
}

AdaptiveCycle cycle_of(const RunReport& report, double seconds) {
  AdaptiveCycle cycle;
  cycle.elements = report.size.elements;
  cycle.dofs = report.size.dofs;
  if (report.error_estimate) {
    cycle.estimate = report.error_estimate->estimate;
    cycle.relative = report.error_estimate->relative;
    cycle.strain_energy = report.error_estimate->strain_energy;
  }
  const bool solid = report.model && report.model->dim == 3;
  if (report.contact.total_force == 0 && !report.pairs.empty()) {  // bodies touching only each other: the first pair
    const PairContact& pair = report.pairs.front();
    cycle.total_force = pair.force_on_node_body.norm();
    cycle.max_pressure = pair.max_pressure;
    cycle.zone = solid ? pair.contact_radius : pair.half_width;
    if (pair.friction) {
      cycle.friction = true;
      cycle.tangential_force = pair.friction->tangential_force;
      cycle.stick_zone = pair.friction->stick_size;
    }
  } else {
    cycle.total_force = report.contact.total_force;
    cycle.max_pressure = report.contact.max_pressure;
    cycle.zone = solid ? report.contact.contact_radius : report.contact.half_width;
    if (report.friction) {
      cycle.friction = true;
      cycle.tangential_force = report.contact.tangential_force;
      cycle.stick_zone = report.contact.stick_size;
    }
  }
  cycle.iterations = report.result.iterations;
  cycle.seconds = seconds;
  return cycle;
}

}  // namespace

RunReport run_adaptive(const Scene& scene, const RunOptions& options) {
  Stopwatch total;
  Scene current = scene;
  check_adaptive_scene(current);
  AdaptiveRun run;
  run.spec = *scene.adapt;
  current.adapt.reset();
  // Each cycle whole on every process: the estimate and the model it plans from are the
  // one-process run's. Under mpirun every rank runs the same cycles (the petsc backend on the
  // problem in parts, K in rank shares; the other backends replicated) and meshes the same
  // next mesh from the same indicators; assemble_par_qp() checks that the ranks' meshes agree.
  RunOptions cycle_options = options;
  cycle_options.distributed = false;
  cycle_options.whole = true;

  std::vector<double> max_size;
  for (const BodySpec* body : scene_bodies(current)) max_size.push_back(body->shape == "mesh" ? 0 : body->mesh.size);

  RunReport report;
  double earlier = 0;  // the cycles before the last
  for (int cycle = 0;; ++cycle) {
    Stopwatch clock;
    report = run_scene(current, cycle_options);
    run.cycles.push_back(cycle_of(report, clock.seconds()));
    const AdaptiveCycle& last = run.cycles.back();
    const std::string reached = percent(last.relative) + " at " + std::to_string(last.dofs) + " DOFs after " +
                                std::to_string(cycle + 1) + (cycle == 0 ? " cycle" : " cycles");
    if (report.result.status != Status::Converged) {
      run.stop = "cycle " + std::to_string(cycle + 1) + " did not converge (" + to_string(report.result.status) + ")";
      break;
    }
    if (!report.error_estimate) {
      run.stop = "cycle " + std::to_string(cycle + 1) + " has no error estimate";
      break;
    }
    if (last.relative <= run.spec.target) {
      run.met = true;
      break;
    }
    if (cycle + 1 >= run.spec.max_cycles) {
      run.stop = "reached " + reached + " (adapt.max_cycles " + std::to_string(run.spec.max_cycles) + ")";
      break;
    }
    // The DOF budget bounds the next mesh's growth: its DOFs are taken to grow with its elements.
    const double dofs_per_element = static_cast<double>(last.dofs) / std::max<long long>(1, last.elements);
    NextMeshLimits limits;
    limits.max_size = max_size;
    limits.max_growth =
        std::min(kMaxGrowth, static_cast<double>(run.spec.max_dofs) / (dofs_per_element * last.elements));
    if (limits.max_growth < 1.1) {
      run.stop =
          "reached " + reached + ": a finer mesh would exceed adapt.max_dofs " + std::to_string(run.spec.max_dofs);
      break;
    }
    const double norm = std::sqrt(2 * last.strain_energy);
    const NextMesh next =
        plan_next_mesh(*report.model, report.error_estimate->indicator, kAim * run.spec.target * norm, limits);
    std::vector<BodySpec*> bodies = scene_bodies(current);
    for (std::size_t b = 0; b < bodies.size(); ++b)
      if (next.size_fields[b]) bodies[b]->mesh.size_field = next.size_fields[b];
    // The next solve starts from this answer (load steps start each path from its beginning).
    const auto warm = std::make_shared<const WarmStart>(*report.model, *report.qp, report.result);
    cycle_options.initial_guess = [warm](const Model& model, const QuadraticProgram& qp) { return (*warm)(model, qp); };
    earlier += report.timings.get("total");
  }
  report.adaptive = std::move(run);
  // The last cycle's phases, the earlier cycles as one phase, and the whole run.
  Timings timings;
  for (const auto& [phase, seconds] : report.timings.phases())
    if (phase != "total") timings.add(phase, seconds);
  timings.add("adapt", earlier);
  timings.add("total", total.seconds());
  report.timings = timings;
  return report;
}

}  // namespace contactqp::detail
