// How run_scene() holds a model's QP when the run spans several processes and its backend
// solves a problem held in parts: each process assembles only its part of K. A library that
// solves such problems registers the way from its own file (src/petsc/ does, for the petsc
// backend under mpirun); without one, every process holds the whole QP.
#pragma once

#include <functional>
#include <memory>

#include "contactqp/certificate.hpp"
#include "contactqp/model.hpp"
#include "contactqp/qp.hpp"

namespace contactqp::detail {

// One process's part of a problem held in parts, and the steps run_scene() takes with it.
class ProblemInParts {
 public:
  virtual ~ProblemInParts() = default;
  // This process's part: K a part of the problem's; f, B, g and the rows as post-processing reads them.
  virtual const QuadraticProgram& part() const = 0;
  // The same, for load steps to change its f, g and friction offset (whole on every process).
  virtual QuadraticProgram& part_to_step() = 0;
  virtual SolveResult solve(const SolveOptions& options) const = 0;  // collective, on part()
  // λ_T with friction (empty reads as 0). Collective.
  virtual Certificate certify(const VectorXd& u, const VectorXd& lambda, const VectorXd& lambda_t,
                              const LinearSolver* K_factor) const = 0;
};

struct PartsAssembly {
  // True when it takes a run with these options (e.g. its backend, on more than one process).
  std::function<bool(const SolveOptions& options)> takes;
  // This process's part of the model's QP (collective).
  std::function<std::shared_ptr<ProblemInParts>(Model& model, const SolveOptions& options)> assemble;
};
void register_parts_assembly(PartsAssembly assembly);

// The part a registered assembly makes of the model's QP when one takes these options, else null.
std::shared_ptr<ProblemInParts> assemble_in_parts(Model& model, const SolveOptions& options);

}  // namespace contactqp::detail
