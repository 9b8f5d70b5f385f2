// Small frictional QPs with answers known independently of the backends: closed forms, an
// enumeration of every stick/slip/contact state (2D), and problems built backwards from a chosen
// KKT point (2D and 3D).
#pragma once

#include <Eigen/Dense>

#include "contactqp/qp.hpp"

namespace contactqp::testing {

struct FrictionSolution {
  Eigen::VectorXd u, lambda, lambda_t;
};

// One node on a rigid plane, held by springs: DOFs (u_t, u_n) in 2D, (u_t1, u_t2, u_n) in 3D,
// K = diag(k_t..., k_n), load f = (q..., −P) (q: tangential load, P: pushing into the plane),
// the row −u_n ≤ gap, T = the tangential DOFs, offset 0. `law`'s value is the threshold s
// (Tresca) or μ (Coulomb).
QuadraticProgram node_on_plane(const Eigen::VectorXd& k_t, double k_n, const Eigen::VectorXd& q, double P, double gap,
                               FrictionLaw law, double value);

// Its answer, by hand: λ_N = max(0, P − k_n gap); radius r = s or μλ_N; stick (u_t = 0,
// λ_T = q) when ‖q‖ ≤ r; otherwise slip u_t,k = q_k/(k_t,k + r/ρ), ρ = ‖u_t‖ the root of
// Σ_k (q_k/(k_t,k ρ + r))² = 1 (bisection; ρ = (‖q‖ − r)/k_t when k_t is isotropic), λ_T = r u_t/ρ.
FrictionSolution node_on_plane_solution(const Eigen::VectorXd& k_t, double k_n, const Eigen::VectorXd& q, double P,
                                        double gap, FrictionLaw law, double value);

// A random 2D Tresca QP: n DOFs, m normal rows and m tangential rows (random unit rows), random
// thresholds and offsets; reproducible from `seed`. Its states mix contact, gap, stick and slip.
QuadraticProgram random_tresca_2d(int n, int m, unsigned seed);

// The exact answer of a 2D Tresca QP with m ≤ 5 by enumerating every state: for each row,
// contact (B_i u = g_i) or gap (λ_N,i = 0), and stick (T_i u = offset_i) or slip at +s or −s
// (λ_T,i = ±s); the linear KKT system of each combination, kept when it is feasible: λ_N ≥ 0,
// B u ≤ g, |λ_T| ≤ s where it sticks, the slip along λ_T where it slips.
FrictionSolution tresca_by_enumeration(const QuadraticProgram& qp);

// A QP built backwards from its solution: nodes with n_directions tangential DOFs and one normal
// DOF each, K random SPD coupling all of them; node i is in contact or not, sticks or slips, by
// a pattern that gives every state; offsets and f are chosen so that the chosen (u, λ, λ_T)
// is its KKT point (Coulomb: with μ = `mu` on every node; Tresca: random thresholds).
struct KnownFrictionQp {
  QuadraticProgram qp;
  FrictionSolution exact;
};
KnownFrictionQp known_friction_qp(int nodes, int n_directions, FrictionLaw law, unsigned seed, double mu = 0.3);

// T for a QP whose rows of B each touch one node's dim DOFs: unit tangents orthogonal to each
// row's normal (in 3D the second one n × t₁): the obstacle rows of a mesh.
Eigen::SparseMatrix<double> tangents_of(const Eigen::SparseMatrix<double>& B, int dim);

}  // namespace contactqp::testing
