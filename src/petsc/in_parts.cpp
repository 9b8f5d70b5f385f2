// run_scene() on several processes with the petsc backend (src/run/problem_in_parts.hpp): each
// rank assembles its share of K (par_qp.hpp), and the solve and the certificate sum over the ranks.
#include "contactqp/backend.hpp"
#include "contactqp/petsc/par_qp.hpp"
#include "contactqp/processes.hpp"
#include "qp/builtins.hpp"
#include "run/problem_in_parts.hpp"

namespace contactqp::detail {
namespace {

class RankShares final : public ProblemInParts {
 public:
  explicit RankShares(ParQuadraticProgram qp) : qp_(std::move(qp)) {}
  const QuadraticProgram& part() const override { return qp_.share; }
  QuadraticProgram& part_to_step() override { return qp_.share; }
  SolveResult solve(const SolveOptions& options) const override { return contactqp::solve(qp_, options); }
  Certificate certify(const VectorXd& u, const VectorXd& lambda, const VectorXd& lambda_t,
                      const LinearSolver* K_factor) const override {
    return contactqp::certify(qp_, u, lambda, lambda_t, K_factor);
  }

 private:
  ParQuadraticProgram qp_;
};

}  // namespace
}  // namespace contactqp::detail

CONTACTQP_BUILTIN(petsc_in_parts) {
  PartsAssembly shares;
  shares.takes = [](const SolveOptions& options) {
    return options.backend == Backend::Petsc && backend_available(Backend::Petsc) && process_count() > 1;
  };
  shares.assemble = [](Model& model, const SolveOptions& options) -> std::shared_ptr<ProblemInParts> {
    // MPI, with the user's PETSc options on PETSc's command line, before the collective partition.
    start_process_runtime(options.library_options);
    return std::make_shared<RankShares>(assemble_par_qp(model, RankShare{process_rank(), process_count(), {}}));
  };
  register_parts_assembly(shares);
}
