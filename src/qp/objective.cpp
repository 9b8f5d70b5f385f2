// K_times() and primal_objective() (qp.hpp): apart from qp.cpp, whose names and checks the
// scene parser's fuzzer links alone, because these sum over the MPI ranks for a rank share.
#include "contactqp/processes.hpp"
#include "contactqp/qp.hpp"

namespace contactqp {

VectorXd K_times(const QuadraticProgram& qp, const VectorXd& u) {
  VectorXd Ku = qp.K * u;
  if (qp.K_is_rank_share) sum_over_ranks(Ku.data(), Ku.size());
  return Ku;
}

double primal_objective(const QuadraticProgram& qp, const VectorXd& u) {
  return 0.5 * u.dot(K_times(qp, u)) - qp.f.dot(u);
}

}  // namespace contactqp
