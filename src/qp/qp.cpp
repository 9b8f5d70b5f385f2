#include "contactqp/qp.hpp"

#include <cmath>

#include "contactqp/errors.hpp"
#include "qp/friction_sets.hpp"
#include "qp/norms.hpp"

namespace contactqp {
namespace {

bool all_finite(const SparseMatrix& A) {
  for (int k = 0; k < A.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(A, k); it; ++it)
      if (!std::isfinite(it.value())) return false;
  return true;
}

std::string shape(const SparseMatrix& A) { return std::to_string(A.rows()) + " × " + std::to_string(A.cols()); }

// Each column r of the null space must satisfy K r ≈ 0: ‖K r‖∞ at most 1e-8 ‖K‖∞ ‖r‖∞ (a rigid
// mode computed from coordinates carries their round-off, far below that), else the caller
// passed modes of another K and the solve would be silently wrong.
void validate_null_space(const QuadraticProgram& qp) {
  if (qp.null_space.cols() == 0) return;
  const double stiffness = infinity_norm(qp.K);
  for (long j = 0; j < qp.null_space.cols(); ++j) {
    const Eigen::VectorXd r = qp.null_space.col(j);
    const double size = r.cwiseAbs().maxCoeff();
    if (size == 0) throw InputError("qp.null_space", "column " + std::to_string(j) + " is zero");
    const double residual = (qp.K * r).cwiseAbs().maxCoeff();
    if (residual > 1e-8 * stiffness * size)
      throw InputError("qp.null_space", "column " + std::to_string(j) +
                                            " is not in K's null space: |K r| = " + format_value(residual) +
                                            " against |K| |r| = " + format_value(stiffness * size));
  }
}

}  // namespace

std::string to_string(FrictionLaw law) {
  switch (law) {
    case FrictionLaw::None:
      return "none";
    case FrictionLaw::Tresca:
      return "tresca";
    case FrictionLaw::Coulomb:
      return "coulomb";
  }
  return "unknown";
}

std::string to_string(ProblemKind kind) {
  switch (kind) {
    case ProblemKind::Frictionless:
      return "frictionless";
    case ProblemKind::Tresca:
      return "tresca";
    case ProblemKind::Coulomb:
      return "coulomb";
  }
  return "unknown";
}

ProblemKind problem_kind(const QuadraticProgram& qp) {
  switch (qp.friction.law) {
    case FrictionLaw::None:
      return ProblemKind::Frictionless;
    case FrictionLaw::Tresca:
      return ProblemKind::Tresca;
    case FrictionLaw::Coulomb:
      return ProblemKind::Coulomb;
  }
  return ProblemKind::Frictionless;
}

std::string to_string(Status status) {
  switch (status) {
    case Status::Converged:
      return "converged";
    case Status::MaxIterations:
      return "max_iterations";
    case Status::Diverged:
      return "diverged";
    case Status::NumericalError:
      return "numerical_error";
    case Status::Inaccurate:
      return "inaccurate";
    case Status::Infeasible:
      return "infeasible";
    case Status::Unbounded:
      return "unbounded";
  }
  return "unknown";
}

void validate(const QuadraticProgram& qp) {
  const long n = qp.K.rows();
  if (qp.K.cols() != n) throw InputError("qp.K", "is " + shape(qp.K) + ": must be square");
  if (qp.f.size() != n)
    throw InputError("qp.f", "has " + std::to_string(qp.f.size()) + " entries, K has " + std::to_string(n) + " rows");
  if (qp.B.cols() != n)
    throw InputError("qp.B", "has " + std::to_string(qp.B.cols()) + " columns, K has " + std::to_string(n) + " rows");
  if (qp.g.size() != qp.B.rows())
    throw InputError("qp.g",
                     "has " + std::to_string(qp.g.size()) + " entries, B has " + std::to_string(qp.B.rows()) + " rows");
  if (!qp.rows.empty() && static_cast<long>(qp.rows.size()) != qp.B.rows())
    throw InputError("qp.rows", "has " + std::to_string(qp.rows.size()) + " entries, B has " +
                                    std::to_string(qp.B.rows()) + " rows");
  if (qp.near_null_space.size() > 0 && qp.near_null_space.rows() != n)
    throw InputError("qp.near_null_space", "has " + std::to_string(qp.near_null_space.rows()) + " rows, K has " +
                                               std::to_string(n) + " rows");
  if (!qp.near_null_space.allFinite()) throw InputError("qp.near_null_space", "has an entry that is not finite");
  if (qp.null_space.size() > 0 && qp.null_space.rows() != n)
    throw InputError("qp.null_space",
                     "has " + std::to_string(qp.null_space.rows()) + " rows, K has " + std::to_string(n) + " rows");
  if (!qp.null_space.allFinite()) throw InputError("qp.null_space", "has an entry that is not finite");
  const CoarseSpace& coarse = qp.coarse_space;
  if (!coarse.empty() && (coarse.interpolation.rows() != n ||
                          coarse.column_vertex.size() != static_cast<std::size_t>(coarse.interpolation.cols()) ||
                          coarse.column_dof.size() != coarse.column_vertex.size()))
    throw InputError("qp.coarse_space", "has " + std::to_string(coarse.interpolation.rows()) + " rows and " +
                                            std::to_string(coarse.interpolation.cols()) +
                                            " columns, which disagree with K's rows or its per-column lists");
  if (!all_finite(qp.K)) throw InputError("qp.K", "has an entry that is not finite");
  if (!all_finite(qp.B)) throw InputError("qp.B", "has an entry that is not finite");
  if (!qp.f.allFinite()) throw InputError("qp.f", "has an entry that is not finite");
  if (!qp.g.allFinite()) throw InputError("qp.g", "has an entry that is not finite");
  detail::validate_friction(qp);
  validate_null_space(qp);
}

}  // namespace contactqp
