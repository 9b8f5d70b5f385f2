#include "multiplier_set.hpp"

#include <vector>

#include "contactqp/errors.hpp"
#include "qp/friction_sets.hpp"

namespace contactqp::detail {

MultiplierSet::MultiplierSet(const QuadraticProgram& qp, const VectorXd& radii, bool always_stacked)
    : m_(qp.n_constraints()), tangential_rows_(static_cast<int>(qp.friction.T.rows())) {
  const bool no_radius = radii.size() == 0 || radii.cwiseAbs().maxCoeff() == 0;
  if (qp.friction.empty() || (no_radius && !always_stacked)) {
    c_ = qp.g;
    C_ = &qp.B;
    c_ptr_ = &c_;
    return;
  }
  n_directions_ = qp.friction.n_directions;
  radii_ = radii.size() ? radii : VectorXd(VectorXd::Zero(m_));
  const SparseMatrix& T = qp.friction.T;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(qp.B.nonZeros() + T.nonZeros());
  for (int j = 0; j < qp.B.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(qp.B, j); it; ++it) entries.emplace_back(it.row(), it.col(), it.value());
  for (int j = 0; j < T.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(T, j); it; ++it) entries.emplace_back(m_ + it.row(), it.col(), it.value());
  stacked_.resize(qp.B.rows() + T.rows(), qp.B.cols());
  stacked_.setFromTriplets(entries.begin(), entries.end());
  c_.resize(stacked_.rows());
  c_ << qp.g, qp.friction.offset;
  C_ = &stacked_;
  c_ptr_ = &c_;
}

VectorXd MultiplierSet::project(const VectorXd& y) const {
  if (!frictional()) return y.cwiseMax(0.0);
  return project_multipliers(y, m_, n_directions_, radii_);
}

VectorXd MultiplierSet::join(const VectorXd& lambda, const VectorXd& lambda_t) const {
  VectorXd y = VectorXd::Zero(rows());
  if (lambda.size()) y.head(m_) = lambda;
  if (frictional() && lambda_t.size()) y.tail(rows() - m_) = lambda_t;
  return project(y);
}

VectorXd initial_multipliers(const QuadraticProgram& qp, const SolveOptions& options, const MultiplierSet& set) {
  const InitialGuess& initial = options.initial;
  if (initial.u.size() != 0 && initial.u.size() != qp.n_dofs())
    throw InputError("initial.u", "has " + std::to_string(initial.u.size()) + " entries, K has " +
                                      std::to_string(qp.n_dofs()) + " rows");
  if (!initial.u.allFinite()) throw InputError("initial.u", "has an entry that is not finite");
  if (initial.lambda.size() == 0 && initial.lambda_t.size() == 0) return VectorXd();
  if (initial.lambda.size() != 0 && initial.lambda.size() != qp.n_constraints())
    throw InputError("initial.lambda", "has " + std::to_string(initial.lambda.size()) + " entries, B has " +
                                           std::to_string(qp.n_constraints()) + " rows");
  const long t_rows = qp.friction.T.rows();
  if (initial.lambda_t.size() != 0 && initial.lambda_t.size() != t_rows)
    throw InputError("initial.lambda_t", "has " + std::to_string(initial.lambda_t.size()) + " entries, expected " +
                                             std::to_string(t_rows) + " (m · n_directions)");
  if (!initial.lambda.allFinite()) throw InputError("initial.lambda", "has an entry that is not finite");
  if (!initial.lambda_t.allFinite()) throw InputError("initial.lambda_t", "has an entry that is not finite");
  return set.join(initial.lambda, initial.lambda_t);
}

}  // namespace contactqp::detail
