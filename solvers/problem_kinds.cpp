// Which backends solve which kinds of problem (friction.hpp's ProblemKind, and with friction the
// dimension), and the one "unsupported" message.
#include "problem_kinds.hpp"

#include "contactqp/errors.hpp"
#include "contactqp/solve.hpp"

namespace contactqp {
namespace {

// The most tangential directions per row a backend's friction method takes: nlopt's bounds
// hold 2D friction's intervals but not 3D's discs (nlopt.cpp says what was tried).
int max_directions(Backend backend) { return backend == Backend::Nlopt ? 1 : 2; }

}  // namespace

bool backend_supports(Backend backend, ProblemKind kind) {
  if (kind == ProblemKind::Frictionless) return true;
  switch (backend) {
    case Backend::Uzawa:
    case Backend::UzawaAccelerated:
    case Backend::ActiveSet:
    case Backend::Ipopt:
    case Backend::Nlopt:
      return true;
    case Backend::Petsc:
      return false;
  }
  return false;
}

bool backend_solves(Backend backend, const QuadraticProgram& qp) {
  return backend_supports(backend, problem_kind(qp)) &&
         (qp.friction.empty() || qp.friction.n_directions <= max_directions(backend));
}

std::vector<Backend> available_backends(ProblemKind kind) {
  std::vector<Backend> list;
  for (Backend backend : available_backends())
    if (backend_supports(backend, kind)) list.push_back(backend);
  return list;
}

std::vector<Backend> available_backends(const QuadraticProgram& qp) {
  std::vector<Backend> list;
  for (Backend backend : available_backends())
    if (backend_solves(backend, qp)) list.push_back(backend);
  return list;
}

namespace detail {

void require_supported(Backend backend, const QuadraticProgram& qp) {
  if (backend_solves(backend, qp)) return;
  const ProblemKind kind = problem_kind(qp);
  const std::string what = backend_supports(backend, kind)
                               ? "3D " + to_string(kind) +
                                     " friction problems (2D only: its bounds hold an interval, "
                                     "not a disc)"
                               : to_string(kind) + " friction problems";
  std::string valid;
  for (Backend other : available_backends(qp)) valid += (valid.empty() ? "" : ", ") + to_string(other);
  throw InputError("backend", "= " + to_string(backend) + ": does not solve " + what + "; backends that do: " + valid);
}

}  // namespace detail
}  // namespace contactqp
