// The steps solve() takes around every backend (solve.cpp), for a library whose problems this
// process holds only part of (src/petsc/'s ParQuadraticProgram): it runs the same steps with its
// own products of K and its own hand-over to the backend, instead of a second copy of them.
#pragma once

#include <functional>

#include "contactqp/qp.hpp"

namespace contactqp::detail {

// How the steps apply K: the QP's own K (whole_K), or a product its library sums over the
// processes that hold K's parts.
struct KOperations {
  std::function<VectorXd(const VectorXd& u)> times;  // K u
  std::function<VectorXd()> diagonal;                // K's diagonal
  // The certificate of (u, λ, λ_T) with K_factor for θ (certificate.hpp; null: no dual),
  // collective where K's products are: solve() certifies every answer once and its status
  // claims no more than that.
  std::function<Certificate(const VectorXd& u, const VectorXd& lambda, const VectorXd& lambda_t,
                            const LinearSolver* K_factor)>
      certify;
  // Whether the QP is whole on this process: only then does solve() look for the evidence of a
  // problem without solution (no_solution.hpp) when the certificate rejects an answer, and only
  // then may a step factorise K itself.
  bool whole = true;
  // The same operations for another QP held like this one (a K this process holds the same part
  // of): the proximal steps on K's free modes (floating.hpp) solve QPs whose K is K_ε.
  std::function<KOperations(const QuadraticProgram& qp)> like;
  // Whether this process adds the proximal steps' springs to its part of K: the parts sum to
  // K, so exactly one process does (every process of a whole K).
  bool adds_springs = true;
};
KOperations whole_K(const QuadraticProgram& qp);  // refers to qp: keep it alive
// K.certify of a result, with its own K_factor.
Certificate certify_result(const KOperations& K, const SolveResult& result);

// Runs the backend on a validated (and scaled) problem.
using BackendSolve = std::function<SolveResult(const QuadraticProgram& qp, const SolveOptions& options)>;

// Validates the QP and the options (backend options and problem kind too), scales, runs
// `backend_solve`, unscales, guards against non-finite and overflowed output, zeros the
// multipliers of separated rows, certifies the answer (and, when the certificate rejects it,
// looks for evidence that no answer exists) and reports the solver of K's statistics: solve()
// is this with whole_K and the backend's registration.
SolveResult solve_with(const QuadraticProgram& qp, const SolveOptions& options, const KOperations& K,
                       const BackendSolve& backend_solve);

}  // namespace contactqp::detail
