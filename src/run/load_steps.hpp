// solve_load_steps() (contactqp/run.hpp) with the solve of each step given: run_scene() passes
// a problem held in parts' own solve (problem_in_parts.hpp) under mpirun, where each step
// changes that part's f, g and friction offset (whole on every process) and not its K.
#pragma once

#include <functional>
#include <vector>

#include "contactqp/run.hpp"

namespace contactqp::detail {

// The steps of solve_load_steps() on `qp`, each solved by solve_step with that step's options
// (warm start and factor of K from the step before); `qp` is the problem solve_step solves.
SolveResult solve_load_steps_with(Model& model, QuadraticProgram& qp, const Scene& scene, const SolveOptions& options,
                                  std::vector<StepReport>* steps,
                                  const std::function<SolveResult(const SolveOptions& options)>& solve_step);

}  // namespace contactqp::detail
