// solve_without_contact(): one linear solve of the contact QP's K, the floor every contact
// solve is compared with (`contactqp solve ... --no-contact`, benchmarks/scaling).
#include "backends.hpp"
#include "contactqp/solve.hpp"
#include "scaling.hpp"

namespace contactqp {

SolveResult solve_without_contact(const QuadraticProgram& qp, const SolveOptions& options) {
  validate(qp);
  Stopwatch clock;
  // The same scaled K as solve() hands a backend, so that the factorisation is the same one.
  const detail::QpScaling scaling = options.scale ? detail::choose_scaling(qp, qp.K.diagonal()) : detail::QpScaling{};
  const QuadraticProgram scaled = options.scale ? detail::scaled_qp(qp, scaling) : qp;
  const SolveOptions scaled_options = options.scale ? detail::scaled_options(options, scaling) : options;

  SolveResult result;
  result.lambda = VectorXd::Zero(qp.n_constraints());
  result.K_factor = detail::factor_of_K(scaled, scaled_options, result.timings, result.message);
  if (result.K_factor) {
    Stopwatch solve_clock;
    result.u = result.K_factor->solve(scaled.f);
    result.timings.add("solve", solve_clock.seconds());
    result.iterations = 1;
    result.status = result.K_factor->ok() ? Status::Converged : Status::NumericalError;
    result.message = result.K_factor->ok() ? "linear solve of K u = f with the contact rows dropped (--no-contact)"
                                           : "the solve with K failed: " + result.K_factor->message();
  } else {
    result.u = VectorXd::Zero(qp.n_dofs());
  }
  detail::report_linear_solver(result);
  if (options.scale) detail::unscale_result(result, scaling);
  result.timings.add("total", clock.seconds());
  return result;
}

}  // namespace contactqp
