// distributed_error_estimate() (distributed_estimate.hpp).
#include "distributed_estimate.hpp"

#include <mpi.h>

#include <algorithm>

#include "contactqp/timer.hpp"
#include "distributed_post.hpp"
#include "post/estimate_sums.hpp"

namespace contactqp::detail {
namespace {

// The nodal pressure of every contact row this rank holds: its own rows' from `own_pressure`,
// a ghost node's rows from the node's owner (whose rows at the node are the same, in the same
// order: the ranks choose candidates alike, distributed_model.hpp).
std::vector<double> row_pressures(const DistributedModel& model, const std::vector<double>& own_pressure) {
  const std::vector<Candidate>& rows = model.local.candidates;
  const int n = model.local.mesh.n_nodes();
  std::vector<int> place(rows.size(), 0);  // each row's place among its node's rows
  std::vector<int> count(n, 0);
  for (std::size_t i = 0; i < rows.size(); ++i) place[i] = count[rows[i].node]++;
  int width = count.empty() ? 0 : *std::max_element(count.begin(), count.end());
  MPI_Allreduce(MPI_IN_PLACE, &width, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  std::vector<double> pressure(rows.size(), 0.0);
  if (width == 0) return pressure;
  std::vector<double> by_node(static_cast<std::size_t>(width) * n, 0.0);
  for (int i = 0; i < model.n_own_candidates; ++i)
    by_node[static_cast<std::size_t>(width) * rows[i].node + place[i]] = own_pressure[i];
  model.shared.from_owner(by_node.data(), width);
  for (std::size_t i = 0; i < rows.size(); ++i)
    pressure[i] = by_node[static_cast<std::size_t>(width) * rows[i].node + place[i]];
  return pressure;
}

bool any_rank(bool mine) {
  int any = mine ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return any != 0;
}

}  // namespace

ErrorEstimate distributed_error_estimate(const DistributedModel& model, const Eigen::VectorXd& local_u,
                                         const std::vector<double>& own_pressure, bool contact) {
  Stopwatch clock;
  const Model& local = model.local;
  const Eigen::VectorXd displacement = full_displacement(local, local_u);
  std::vector<double> pressure;
  Eigen::VectorXd slack;
  if (contact) {
    pressure = row_pressures(model, own_pressure);
    slack = row_slacks(local, local_u);
  }
  const SumOverShared sum_shared = [&model](double* values, int width) { model.shared.sum(values, width); };
  const EstimateSums mine = estimate_sums(local, displacement, pressure, slack, nullptr, nullptr, sum_shared);
  double totals[5] = {mine.energy, mine.recovery, mine.contact, mine.friction, mine.total};
  MPI_Allreduce(MPI_IN_PLACE, totals, 5, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  EstimateSums all;
  all.energy = totals[0];
  all.recovery = totals[1];
  all.contact = totals[2];
  all.friction = totals[3];
  all.total = totals[4];
  // As the one-process estimate decides it (estimate_error()): pushed by prescribed
  // displacements alone, linear elements, contact rows (the distributed run is frictionless).
  const bool pushed = any_rank(local.prescribed.size() && local.prescribed.cwiseAbs().maxCoeff() > 0);
  const bool forced = any_rank(local.nodal_force.size() && local.nodal_force.cwiseAbs().maxCoeff() > 0);
  const bool force_estimate = pushed && !forced && local.mesh.order == 1 && contact && model.n_global_candidates > 0;
  ErrorEstimate estimate = estimate_from_sums(all, mine.squared, force_estimate);
  MPI_Allreduce(MPI_IN_PLACE, &estimate.max_indicator, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  estimate.seconds = clock.seconds();
  return estimate;
}

double distributed_strain_energy(const DistributedModel& model, const Eigen::VectorXd& local_u) {
  double energy = strain_energy(model.local, local_u);
  MPI_Allreduce(MPI_IN_PLACE, &energy, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  return energy;
}

}  // namespace contactqp::detail
