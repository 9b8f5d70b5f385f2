// A downstream user of the installed contactqp: one small QP with a hand-solved answer,
// solved by every backend this copy was built with, each answer certified.
//
//   minimise u0² − u0 u1 + u1² − u0 − u1   subject to   u0 ≤ 0.5
//
// The free optimum (1, 1) violates the row; on it 2 u1 − 0.5 = 1 gives u1 = 0.75, and
// stationarity of row 0 (2·0.5 − 0.75 − 1 + λ = 0) gives λ = 0.75.
#include <cmath>
#include <cstdio>

#include <contactqp/certificate.hpp>
#include <contactqp/solve.hpp>

int main() {
  using namespace contactqp;
  QuadraticProgram qp;
  qp.K.resize(2, 2);
  qp.K.insert(0, 0) = 2.0;
  qp.K.insert(0, 1) = -1.0;
  qp.K.insert(1, 0) = -1.0;
  qp.K.insert(1, 1) = 2.0;
  qp.f = Eigen::Vector2d(1.0, 1.0);
  qp.B.resize(1, 2);
  qp.B.insert(0, 0) = 1.0;
  qp.g = Eigen::VectorXd::Constant(1, 0.5);

  int failures = 0;
  for (const Backend backend : available_backends()) {
    SolveOptions options;
    options.backend = backend;
    options.tol = 1e-10;
    const SolveResult result = solve(qp, options);
    const Certificate certificate = certify(qp, result.u, result.lambda);
    const double error =
        std::max({std::abs(result.u[0] - 0.5), std::abs(result.u[1] - 0.75), std::abs(result.lambda[0] - 0.75)});
    const bool ok = result.status == Status::Converged && error < 1e-8 && certificate.kkt_max() < 1e-8;
    std::printf("%-12s %-10s u = (%.10f, %.10f), lambda = %.10f, KKT %.1e: %s\n", to_string(backend).c_str(),
                to_string(result.status).c_str(), result.u[0], result.u[1], result.lambda[0], certificate.kkt_max(),
                ok ? "ok" : "WRONG");
    failures += ok ? 0 : 1;
  }
  return failures == 0 ? 0 : 1;
}
