// Load steps (docs/friction.md): quasi-static and incremental. Each step solves for the state at
// its end from the state the last one left: with friction the slip of a step is the tangential
// displacement since the last step, so a node that sticks keeps its tangential offset.
#include "run/load_steps.hpp"
#include "contact/contact.hpp"
#include "contactqp/run.hpp"
#include "contactqp/solve.hpp"

namespace contactqp {

PostProcessed postprocess(const Model& model, const QuadraticProgram& qp, const SolveResult& result) {
  PostProcessed state;
  state.contact = summarize_contact(model, qp, result.u, result.lambda);
  state.reactions = reactions(model, qp, result.u, result.lambda, result.lambda_t);
  state.pairs = summarize_pairs(model, qp, result.u, result.lambda);
  if (!qp.friction.empty() && result.lambda_t.size() == qp.friction.T.rows()) {
    state.friction = friction_fields(model, qp, result.u, result.lambda, result.lambda_t);
    summarize_friction(model, *state.friction, state.contact, state.pairs);
  }
  return state;
}

SolveResult solve_load_steps(Model& model, QuadraticProgram& qp, const Scene& scene, const SolveOptions& options,
                             std::vector<StepReport>* steps) {
  return detail::solve_load_steps_with(model, qp, scene, options, steps,
                                       [&qp](const SolveOptions& step_options) { return solve(qp, step_options); });
}

namespace detail {

SolveResult solve_load_steps_with(Model& model, QuadraticProgram& qp, const Scene& scene, const SolveOptions& options,
                                  std::vector<StepReport>* steps,
                                  const std::function<SolveResult(const SolveOptions& options)>& solve_step) {
  const std::vector<std::vector<double>> factors = load_factors(scene);
  std::vector<std::string> names;  // the named loads, in load order
  for (const LoadSpec& load : model.scene.loads) names.push_back(load.name);
  const bool friction = !qp.friction.empty();
  Eigen::VectorXd positions = Eigen::VectorXd::Zero(friction ? qp.friction.T.rows() : 0);
  SolveOptions step_options = options;
  SolveResult result;
  Timings timings;  // every step's phases added up
  int iterations = 0;
  for (size_t k = 0; k < factors.size(); ++k) {
    const std::string& path = scene.steps[k].path;
    apply_load_step(model, qp, factors[k], path);
    if (friction) detail::set_friction_offset(model, qp, positions);
    Stopwatch clock;
    result = solve_step(step_options);
    const double seconds = clock.seconds();
    timings.merge(result.timings);
    iterations += result.iterations;
    if (friction) positions = detail::tangential_positions(model, result.u);
    // K is the same in every step: the next step reuses this one's factor and starts from its answer.
    step_options.K_factor = result.K_factor;
    step_options.initial = {result.u, result.lambda, result.lambda_t};
    if (steps) {
      StepReport step;
      step.path = path;
      for (size_t l = 0; l < names.size(); ++l)
        if (!names[l].empty()) step.factors.emplace_back(names[l], factors[k][l]);
      step.status = result.status;
      step.message = result.message;
      step.iterations = result.iterations;
      step.seconds = seconds;
      step.diagnostics = result.diagnostics;
      PostProcessed state = postprocess(model, qp, result);
      step.contact = std::move(state.contact);
      step.pairs = std::move(state.pairs);
      step.reactions = std::move(state.reactions);
      steps->push_back(std::move(step));
    }
    if (result.status != Status::Converged) break;  // a later step would start from a wrong state
  }
  result.timings = timings;
  result.iterations = iterations;
  return result;
}

}  // namespace detail

}  // namespace contactqp
