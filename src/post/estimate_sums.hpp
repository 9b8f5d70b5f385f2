// The energy-error estimate (contactqp/estimate.hpp) in two halves, so that a distributed run
// computes it on each rank's part and adds the parts up (docs/estimate.md, "Under mpirun"):
// estimate_sums() on one part, estimate_from_sums() on the sums over every part. The
// one-process estimate_error() is the two on the whole model.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "contactqp/estimate.hpp"
#include "contactqp/friction.hpp"

namespace contactqp::detail {

// Adds each node's `width` values up over the processes that hold the node (SharedNodes::sum);
// empty on one process.
using SumOverShared = std::function<void(double* values, int width)>;

// What the estimate adds up: the strain energy, the squared parts (recovery, contact faces,
// their friction share), the elements' squared indicators summed (η², the faces' terms on
// their elements), and each element's squared indicator (this part's elements).
struct EstimateSums {
  double energy = 0, recovery = 0, contact = 0, friction = 0, total = 0;
  Eigen::VectorXd squared;
};

// One part's sums: `displacement` at every node of model.mesh (full_displacement()), and per
// contact row of model.candidates its nodal pressure and its slack g − B u (both empty: no
// contact terms); `friction_rows` and `friction` with friction (else nullptr). A contact face
// counts on the part that holds its element, with the rows of its nodes there.
EstimateSums estimate_sums(const Model& model, const Eigen::VectorXd& displacement, const std::vector<double>& pressure,
                           const Eigen::VectorXd& slack, const FrictionBlock* friction_rows,
                           const FrictionFields* friction, const SumOverShared& sum_shared = {});

// The estimate from the sums over every part, with `indicator_squared` this part's elements'
// squared indicators; `force_estimate`: whether the contact force's estimate applies (a
// frictionless scene pushed by prescribed displacements alone, linear elements, contact rows).
ErrorEstimate estimate_from_sums(const EstimateSums& sums, const Eigen::VectorXd& indicator_squared,
                                 bool force_estimate);

}  // namespace contactqp::detail
