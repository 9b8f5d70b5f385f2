// One QP solved by every backend this build has, each checked against a reference answer: the
// cross-check that the force and moment scenes share (docs/backends.md).
#pragma once

#include <catch2/catch.hpp>

#include "contactqp/solve.hpp"

namespace contactqp::testing {

// Each available backend must converge and agree with `reference`: u to 1e-6 and λ to 1e-5 of
// their largest entries. Returns how many converged.
inline int every_backend_agrees(const QuadraticProgram& qp, SolveOptions options, const SolveResult& reference) {
  int solved = 0;
  for (const Backend backend : available_backends(qp)) {
    options.backend = backend;
    const SolveResult run = solve(qp, options);
    INFO(to_string(backend) << ": " << run.message);
    CHECK(run.status == Status::Converged);
    if (run.status != Status::Converged) continue;
    ++solved;
    CHECK((run.u - reference.u).cwiseAbs().maxCoeff() <= 1e-6 * reference.u.cwiseAbs().maxCoeff());
    CHECK((run.lambda - reference.lambda).cwiseAbs().maxCoeff() <= 1e-5 * reference.lambda.cwiseAbs().maxCoeff());
  }
  return solved;
}

}  // namespace contactqp::testing
