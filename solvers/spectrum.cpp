#include "spectrum.hpp"

#include <cmath>

namespace contactqp::detail {

SpectrumEstimate estimate_lambda_max(const QuadraticProgram& qp, const CholeskyFactor& K_factor,
                                     double rel_tol, int max_steps) {
  SpectrumEstimate estimate;
  Stopwatch clock;
  const int m = qp.n_constraints();
  if (m == 0) return estimate;

  // A start vector with a component along every eigenvector in practice: all ones plus a
  // deterministic ripple, so that results are reproducible run to run.
  VectorXd v(m);
  for (int i = 0; i < m; ++i) v[i] = 1.0 + 0.5 * std::sin(1.0 + 7.0 * i);
  v.normalize();

  double previous = 0;
  for (int step = 0; step < max_steps; ++step) {
    const VectorXd Sv = qp.B * K_factor.solve(VectorXd(qp.B.transpose() * v));
    ++estimate.applications;
    const double rayleigh = v.dot(Sv);
    const double norm = Sv.norm();
    if (!(norm > 0) || !std::isfinite(norm)) break;  // S v = 0: B has empty rows only
    estimate.lambda_max = rayleigh;
    v = Sv / norm;
    if (step > 2 && std::abs(rayleigh - previous) <= rel_tol * std::abs(rayleigh)) break;
    previous = rayleigh;
  }
  estimate.seconds = clock.seconds();
  return estimate;
}

}  // namespace contactqp::detail
