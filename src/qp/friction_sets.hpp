// The sets the tangential multipliers live in, and the measures of the tangential condition:
// one definition shared by the certificate (src/qp/certificate.cpp) and the backends (solvers/).
//
// Row i's tangential multiplier λ_T,i (n_directions entries, stored at i·n_directions + k) lies
// in the disc D_i of radius r_i: r_i = threshold_i (Tresca), r_i = μ_i max(0, λ_N,i) (Coulomb).
// In 2D the disc is the interval [−r_i, r_i]. The tangential condition is the fixed point of the
// natural map: λ_T,i = proj_{D_i}(λ_T,i + ρ·slip_i) for any ρ > 0, with slip = T u − offset —
// stick (‖λ_T,i‖ < r_i, slip_i = 0) or slip (λ_T,i = r_i slip_i/‖slip_i‖).
#pragma once

#include <Eigen/Core>

#include "contactqp/qp.hpp"

namespace contactqp::detail {

// Projects the block x[0 .. n_directions) onto the disc of radius `radius` ≥ 0, in place.
void project_on_disc(double* x, int n_directions, double radius);

// y = (λ_N, λ_T) (m + m · n_directions entries) projected onto λ_N ≥ 0 and the discs.
Eigen::VectorXd project_multipliers(const Eigen::VectorXd& y, int m, int n_directions, const Eigen::VectorXd& radii);

// The radii r_i of the discs (m entries): the thresholds (Tresca) or μ_i max(0, λ_N,i)
// (Coulomb); empty without friction.
Eigen::VectorXd disc_radii(const FrictionBlock& friction, const Eigen::VectorXd& lambda);

// The slip of this step, T u − offset (m · n_directions).
Eigen::VectorXd slip_of(const FrictionBlock& friction, const Eigen::VectorXd& u);

// Σ_i r_i ‖slip_i‖: the friction term of the primal objective (energy units).
double dissipation(const FrictionBlock& friction, const Eigen::VectorXd& radii, const Eigen::VectorXd& slip);

// max_i ‖λ_T,i − proj_{D_i}(λ_T,i + ρ slip_i)‖₂, in force units: zero exactly where the
// tangential condition holds.
double natural_map_residual(const FrictionBlock& friction, const Eigen::VectorXd& lambda_t,
                            const Eigen::VectorXd& radii, const Eigen::VectorXd& slip, double rho);

// True when the block exerts no tangential force whatever the answer: no law, Tresca with every
// threshold 0 or Coulomb with every μ 0. Backends then solve the frictionless problem (λ_T = 0),
// so that μ = 0 gives today's numbers exactly.
bool without_friction_force(const FrictionBlock& friction);

// The problem's friction block validated against B and K (qp.hpp's validate() calls it).
void validate_friction(const QuadraticProgram& qp);

}  // namespace contactqp::detail
