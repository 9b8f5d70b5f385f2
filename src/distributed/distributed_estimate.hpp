// The energy-error estimate of a distributed solution (docs/estimate.md, "Under mpirun"): each
// rank's part by the one-process estimator (post/estimate_sums.hpp) — its own elements, the
// recovered stress at a node averaged over the elements of every rank that holds it, the contact
// faces of its elements with the rows of their nodes — and the sums reduced over the ranks, so
// that 1, 2 and 4 ranks give one process's estimate.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "contactqp/estimate.hpp"
#include "distributed_model.hpp"

namespace contactqp::detail {

// `local_u`: the free DOFs of all of this rank's nodes (local_free_values()); `own_pressure`:
// the nodal pressure of each own contact row (distributed_contact_summary()); `contact`: false
// for a run without contact (no face terms). The indicator holds this rank's elements.
// Collective.
ErrorEstimate distributed_error_estimate(const DistributedModel& model, const Eigen::VectorXd& local_u,
                                         const std::vector<double>& own_pressure, bool contact);

// The strain energy alone (a run whose estimate is turned off). Collective.
double distributed_strain_energy(const DistributedModel& model, const Eigen::VectorXd& local_u);

}  // namespace contactqp::detail
