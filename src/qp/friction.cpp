// The friction block: its validation and the measures every layer shares (friction_sets.hpp).
#include <algorithm>
#include <cmath>
#include <string>

#include "contactqp/errors.hpp"
#include "qp/friction_sets.hpp"

namespace contactqp {

namespace detail {
namespace {

std::string count(long n) { return std::to_string(n); }

// A vector of the friction block: `expected` entries (or none, when `may_be_empty`), finite,
// and ≥ 0 when `non_negative`; the message names the field and the first bad entry.
void check_vector(const Eigen::VectorXd& v, const std::string& field, long expected, const std::string& why,
                  bool non_negative) {
  if (v.size() != expected)
    throw InputError(field, "has " + count(v.size()) + " entries, expected " + count(expected) + " (" + why + ")");
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i]))
      throw InputError(field + "[" + count(i) + "]", "= " + format_value(v[i]) + ": must be finite");
    if (non_negative && v[i] < 0)
      throw InputError(field + "[" + count(i) + "]", "= " + format_value(v[i]) + ": must be ≥ 0");
  }
}

}  // namespace

void validate_friction(const QuadraticProgram& qp) {
  const FrictionBlock& friction = qp.friction;
  const long m = qp.B.rows(), n = qp.K.rows();
  if (friction.empty()) {
    // Data without a law is a mistake (a law forgotten), not something to ignore silently.
    if (friction.n_directions != 0 || friction.T.size() != 0 || friction.offset.size() != 0 ||
        friction.threshold.size() != 0 || friction.coefficient.size() != 0)
      throw InputError("qp.friction.law", "= none, but the friction block holds data; set the law (tresca, coulomb)");
    return;
  }
  const int nd = friction.n_directions;
  require(nd == 1 || nd == 2, "qp.friction.n_directions", nd, "must be 1 (2D) or 2 (3D)");
  const long rows = m * nd;
  if (friction.T.rows() != rows || friction.T.cols() != n)
    throw InputError("qp.friction.T", "is " + count(friction.T.rows()) + " × " + count(friction.T.cols()) +
                                          ", expected " + count(rows) + " × " + count(n) +
                                          " (n_directions rows per row of B, a column per DOF)");
  for (int k = 0; k < friction.T.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(friction.T, k); it; ++it)
      if (!std::isfinite(it.value())) throw InputError("qp.friction.T", "has an entry that is not finite");
  check_vector(friction.offset, "qp.friction.offset", rows, "n_directions per row of B", false);
  const bool tresca = friction.law == FrictionLaw::Tresca;
  const Eigen::VectorXd& used = tresca ? friction.threshold : friction.coefficient;
  const Eigen::VectorXd& unused = tresca ? friction.coefficient : friction.threshold;
  const std::string used_name = tresca ? "qp.friction.threshold" : "qp.friction.coefficient";
  const std::string unused_name = tresca ? "qp.friction.coefficient" : "qp.friction.threshold";
  check_vector(used, used_name, m, "one per row of B", true);
  if (unused.size() != 0)
    throw InputError(unused_name, "has " + count(unused.size()) + " entries: must be empty under " +
                                      to_string(friction.law) + "'s law (a threshold or a coefficient, not both)");
}

bool without_friction_force(const FrictionBlock& friction) {
  switch (friction.law) {
    case FrictionLaw::None:
      return true;
    case FrictionLaw::Tresca:
      return friction.threshold.size() == 0 || friction.threshold.cwiseAbs().maxCoeff() == 0;
    case FrictionLaw::Coulomb:
      return friction.coefficient.size() == 0 || friction.coefficient.cwiseAbs().maxCoeff() == 0;
  }
  return true;
}

void project_on_disc(double* x, int n_directions, double radius) {
  double norm2 = 0;
  for (int k = 0; k < n_directions; ++k) norm2 += x[k] * x[k];
  if (norm2 <= radius * radius) return;
  const double factor = radius / std::sqrt(norm2);
  for (int k = 0; k < n_directions; ++k) x[k] *= factor;
}

Eigen::VectorXd project_multipliers(const Eigen::VectorXd& y, int m, int n_directions, const Eigen::VectorXd& radii) {
  Eigen::VectorXd p = y;
  p.head(m) = p.head(m).cwiseMax(0.0);
  for (int i = 0; i < m; ++i) project_on_disc(p.data() + m + i * n_directions, n_directions, radii[i]);
  return p;
}

Eigen::VectorXd disc_radii(const FrictionBlock& friction, const Eigen::VectorXd& lambda) {
  switch (friction.law) {
    case FrictionLaw::None:
      return Eigen::VectorXd();
    case FrictionLaw::Tresca:
      return friction.threshold;
    case FrictionLaw::Coulomb:
      return friction.coefficient.cwiseProduct(lambda.cwiseMax(0.0));
  }
  return Eigen::VectorXd();
}

Eigen::VectorXd slip_of(const FrictionBlock& friction, const Eigen::VectorXd& u) {
  return friction.T * u - friction.offset;
}

double dissipation(const FrictionBlock& friction, const Eigen::VectorXd& radii, const Eigen::VectorXd& slip) {
  const int nd = friction.n_directions;
  double sum = 0;
  for (Eigen::Index i = 0; i < radii.size(); ++i) sum += radii[i] * slip.segment(i * nd, nd).norm();
  return sum;
}

double natural_map_residual(const FrictionBlock& friction, const Eigen::VectorXd& lambda_t,
                            const Eigen::VectorXd& radii, const Eigen::VectorXd& slip, double rho) {
  const int nd = friction.n_directions;
  double worst = 0;
  for (Eigen::Index i = 0; i < radii.size(); ++i) {
    double v[2], d2 = 0;
    for (int k = 0; k < nd; ++k) v[k] = lambda_t[i * nd + k] + rho * slip[i * nd + k];
    project_on_disc(v, nd, radii[i]);
    for (int k = 0; k < nd; ++k) d2 += (lambda_t[i * nd + k] - v[k]) * (lambda_t[i * nd + k] - v[k]);
    worst = std::max(worst, std::sqrt(d2));
  }
  return worst;
}

}  // namespace detail
}  // namespace contactqp
