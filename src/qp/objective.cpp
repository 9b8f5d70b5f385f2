// K_times() and primal_objective() (qp.hpp).
#include "contactqp/qp.hpp"

namespace contactqp {

VectorXd K_times(const QuadraticProgram& qp, const VectorXd& u) { return qp.K * u; }

double primal_objective(const QuadraticProgram& qp, const VectorXd& u) {
  return 0.5 * u.dot(K_times(qp, u)) - qp.f.dot(u);
}

}  // namespace contactqp
