// compare_scene(): one QP, several backends, the same certificate for each, and how far their
// answers lie from each other (run.hpp). A dual method and a primal one that agree to the
// tolerance validate each other.
#include <algorithm>
#include <cmath>
#include <limits>

#include "contactqp/certificate.hpp"
#include "contactqp/cholesky.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/run.hpp"
#include "contactqp/solve.hpp"
#include "qp/norms.hpp"

namespace contactqp {
namespace {

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

bool converged(const BackendRun& run) { return run.result.status == Status::Converged; }

// The multipliers a comparison measures: λ, and with friction (λ_N, λ_T) together.
VectorXd multipliers(const BackendRun& run) {
  if (run.result.lambda_t.size() == 0) return run.result.lambda;
  VectorXd joined(run.result.lambda.size() + run.result.lambda_t.size());
  joined << run.result.lambda, run.result.lambda_t;
  return joined;
}

// The converged run with the smallest certified |relative gap|; the run with a certificate
// otherwise. -1 when no run has a dual objective to compare.
int choose_reference(const std::vector<BackendRun>& runs) {
  int best = -1;
  auto better = [&](int i) {
    if (!runs[i].certificate.dual_available) return false;
    if (best < 0) return true;
    if (converged(runs[i]) != converged(runs[best])) return converged(runs[i]);
    return std::abs(runs[i].certificate.relative_gap) < std::abs(runs[best].certificate.relative_gap);
  };
  for (int i = 0; i < static_cast<int>(runs.size()); ++i)
    if (better(i)) best = i;
  return best;
}

}  // namespace

Agreement agreement_for(double tol) { return {1e4 * tol, 1e5 * tol, 1e2 * tol}; }

CompareReport compare_scene(const Scene& scene, const CompareOptions& options) {
  Stopwatch total;
  for (Backend backend : options.backends) {
    SolveOptions checked = scene.solver;
    checked.backend = backend;
    validate_options(checked);
  }

  CompareReport report;
  auto model = std::make_shared<Model>(build_model(scene, options.build));
  auto qp = std::make_shared<QuadraticProgram>(assemble_qp(*model));
  // Every available backend that solves this problem (its kind and, with friction, its dimension;
  // backend.hpp), or the ones listed, each of which must: checked before any solve.
  const std::vector<Backend> backends = options.backends.empty() ? available_backends(*qp) : options.backends;
  std::vector<SolveOptions> solve_options;
  for (Backend backend : backends) {
    if (!backend_solves(backend, *qp)) {
      std::string valid;
      for (Backend other : available_backends(*qp)) valid += (valid.empty() ? "" : ", ") + to_string(other);
      throw InputError("--backends", "= " + to_string(backend) + ": does not solve this scene's " +
                                         (qp->friction.n_directions == 2 ? "3D " : "") + to_string(problem_kind(*qp)) +
                                         " friction problem; backends that do: " + valid);
    }
    solve_options.push_back(scene.solver);
    solve_options.back().backend = backend;
  }
  report.tol = scene.solver.tol;
  report.warnings = model->warnings;

  // The unit of cost (docs/architecture.md): one factorisation of K and one solve with it.
  // The same factor certifies every run, so that all are judged by the same numbers.
  Stopwatch clock;
  const CholeskyFactor K_factor(qp->K);
  report.factorize_seconds = clock.seconds();
  report.linear_solve_seconds = K_factor.ok() ? std::numeric_limits<double>::infinity() : kNone;
  for (int k = 0; k < 5 && K_factor.ok(); ++k) {  // the fastest of a few: the first one warms caches
    clock.restart();
    K_factor.solve(qp->f);
    report.linear_solve_seconds = std::min(report.linear_solve_seconds, clock.seconds());
  }

  // Each backend from scratch (its own factorisation included), so that the times compare. A
  // scene with load steps runs its whole path per backend (with friction the answer depends on
  // it), on its own copy of the model and the QP; the last step's answers are compared, each
  // certified on the QP of its own last step (the offset is that backend's last-but-one step).
  std::shared_ptr<const Model> last_model = model;
  std::shared_ptr<const QuadraticProgram> last_qp = qp;
  for (const SolveOptions& run_options : solve_options) {
    BackendRun run;
    run.backend = run_options.backend;
    if (scene.steps.empty()) {
      run.result = solve(*qp, run_options);
    } else {
      auto step_model = std::make_shared<Model>(*model);
      auto step_qp = std::make_shared<QuadraticProgram>(*qp);
      run.result = solve_load_steps(*step_model, *step_qp, scene, run_options);
      last_model = step_model;
      last_qp = step_qp;
    }
    run.result.K_factor.reset();  // a factor per backend is memory the next one may need
    const Model& run_model = *last_model;
    const QuadraticProgram& run_qp = *last_qp;
    run.certificate = run.result.certificate
                          ? *run.result.certificate
                          : certify(run_qp, run.result.u, run.result.lambda, run.result.lambda_t, &K_factor);
    run.contact = summarize_contact(run_model, run_qp, run.result.u, run.result.lambda);
    if (!run_model.bodies.empty() && run_model.scene.obstacles.empty()) {
      // Bodies without obstacles: the table's zone is the first pair's.
      const std::vector<PairContact> pairs = summarize_pairs(run_model, run_qp, run.result.u, run.result.lambda);
      if (!pairs.empty()) {
        run.contact.total_force = pairs[0].total_force;
        run.contact.half_width = pairs[0].half_width;
        run.contact.contact_radius = pairs[0].contact_radius;
        run.contact.max_pressure = pairs[0].max_pressure;
        run.contact.contact_nodes = pairs[0].contact_nodes;
      }
    }
    report.runs.push_back(std::move(run));
  }

  report.model = last_model;  // with load steps, the last step's (loads, offset) of the last backend
  report.qp = last_qp;
  std::vector<BackendRun>& runs = report.runs;
  report.reference = choose_reference(runs);
  if (report.reference >= 0)
    for (BackendRun& run : runs) {
      run.rel_diff_u = relative_difference(run.result.u, runs[report.reference].result.u);
      run.rel_diff_lambda = relative_difference(multipliers(run), multipliers(runs[report.reference]));
    }

  // Agreement only when every run converged, every certified gap is small and every pair agrees.
  report.bound = agreement_for(scene.solver.tol);
  report.all_converged = true;
  for (size_t i = 0; i < runs.size(); ++i) {
    report.all_converged = report.all_converged && converged(runs[i]) && runs[i].certificate.dual_available;
    report.max_gap = std::max(report.max_gap, std::abs(runs[i].certificate.relative_gap));
    for (size_t j = 0; j < i; ++j) {
      report.max_diff_u = std::max(report.max_diff_u, symmetric_difference(runs[i].result.u, runs[j].result.u));
      report.max_diff_lambda =
          std::max(report.max_diff_lambda, symmetric_difference(multipliers(runs[i]), multipliers(runs[j])));
    }
  }
  report.agree = report.all_converged && report.max_diff_u <= report.bound.u &&
                 report.max_diff_lambda <= report.bound.lambda && report.max_gap <= report.bound.gap;

  report.timings.add("mesh", model->timings.get("mesh"));
  report.timings.add("assemble", model->timings.get("assemble"));
  report.timings.add("total", total.seconds());
  return report;
}

CompareReport compare_scene(const std::string& scene_path, const CompareOptions& options) {
  return compare_scene(load_scene(scene_path), options);
}

}  // namespace contactqp
