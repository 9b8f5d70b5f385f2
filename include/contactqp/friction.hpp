// Friction in the quadratic program: Tresca's law (a given slip threshold) and Coulomb's (a
// threshold μ λ_N), as one block of QuadraticProgram that is empty when a scene has no friction.
//
// Tresca's problem is convex and keeps the QP's shape: its dual is today's dual with more rows,
// whose multipliers live in a disc (a box in 2D) instead of on the half-line λ ≥ 0.
//
//     minimise  ½ uᵀKu − fᵀu + Σ_i s_i ‖(T u − offset)_i‖     subject to   B u ≤ g
//
// with s_i = threshold_i (Tresca) and (T u − offset)_i the slip of contact row i's node in this
// load step (quasi-static, incremental: offset = T u_prev). Lagrangian
//
//     L(u, λ_N, λ_T) = J(u) + λ_Nᵀ(B u − g) + λ_Tᵀ(T u − offset),   λ_N ≥ 0,  ‖λ_T,i‖ ≤ s_i,
//
// stationarity K u − f + Bᵀλ_N + Tᵀλ_T = 0 and dual function θ = −½ rᵀK⁻¹r − gᵀλ_N − offsetᵀλ_T
// with r = f − Bᵀλ_N − Tᵀλ_T. Where a node slips, λ_T,i = s_i · slip_i/‖slip_i‖ (λ_T points along
// the slip; the friction force on the body, −Tᵀλ_T, opposes it); where it sticks, slip_i = 0 and
// ‖λ_T,i‖ ≤ s_i. Coulomb's law takes s_i = μ_i λ_N,i: not an optimisation problem, solved as the
// fixed point of Tresca problems (docs/friction.md).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>

namespace contactqp {

enum class FrictionLaw {
  None,     // frictionless: the block is empty and every number is today's
  Tresca,   // ‖λ_T,i‖ ≤ threshold_i, a given force per contact row
  Coulomb,  // ‖λ_T,i‖ ≤ coefficient_i · λ_N,i
};

// The kinds of problem a backend may support (its registration lists them).
enum class ProblemKind { Frictionless, Tresca, Coulomb };

std::string to_string(FrictionLaw law);   // "none", "tresca", "coulomb"
std::string to_string(ProblemKind kind);  // "frictionless", "tresca", "coulomb"

struct FrictionBlock {
  FrictionLaw law = FrictionLaw::None;
  int n_directions = 0;  // tangential directions per contact row: 1 in 2D, 2 in 3D; 0 without friction
  // (m · n_directions) × n: row i·n_directions + k is t_kᵀ at the DOFs of contact row i's node
  // (between two bodies t_kᵀ(u_i − Σ_j N_j(ξ) u_j)); the t_k are unit vectors orthogonal to the
  // row's normal (between two bodies the common normal along which the sides meet, which may
  // lean off B's face normal) and to each other.
  Eigen::SparseMatrix<double> T;
  // m · n_directions: the tangential position at the start of this load step (T u_prev), so that
  // T u − offset is the step's slip. Zero for the first step.
  Eigen::VectorXd offset;
  Eigen::VectorXd threshold;    // m: Tresca, s·w_i (force; w_i the node's tributary length or area)
  Eigen::VectorXd coefficient;  // m: Coulomb, μ_i ≥ 0

  bool empty() const { return law == FrictionLaw::None; }
};

}  // namespace contactqp
