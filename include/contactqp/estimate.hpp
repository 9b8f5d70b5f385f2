// An a-posteriori estimate of the energy error of a solution (docs/estimate.md), computed after
// the solve from the mesh, the displacement and the contact multipliers alone.
//
//     η² = Σ_T η_T²,   η_T² = ∫_T (σ* − σ_h) : C⁻¹ : (σ* − σ_h)          (recovery, Zienkiewicz–Zhu)
//                           + Σ_{F ⊂ ∂T ∩ Γ_C} [ 2 ∫_F p_h |s_h|          (complementarity of p and the gap)
//                                              + (E*/h_F) ∫_F (s_h⁻)²     (penetration between nodes)
//                                              + 2 ∫_F (b_h |w_h| + q_h·w_h)⁺ ]   (friction's mismatch)
//
// σ_h is the element's stress, σ* its nodal average interpolated with the element's own shape
// functions; p_h, s_h, q_h, b_h and w_h the contact pressure, the deformed gap, the friction
// traction, its bound and the step's slip along a contact face. The energy norm is the one
// whose square is twice the strain energy: ‖v‖² = ∫ ε(v) : C : ε(v) (per the thickness in 2D).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "contactqp/model.hpp"
#include "contactqp/post.hpp"
#include "contactqp/qp.hpp"

namespace contactqp {

struct ErrorEstimate {
  // ½ ∫ ε(u_h) : C : ε(u_h) of the whole displacement, prescribed displacements included (energy;
  // 2D: for the thickness): ½ uᵀKu over every DOF, comparable from one mesh to the next of a
  // scene (the QP's objective drops the constant ½ u_pᵀ K_pp u_p and adds −fᵀu).
  double strain_energy = 0;
  double estimate = 0;  // η, the energy-norm estimate (sqrt of energy)
  double recovery = 0;  // the recovery part, sqrt(Σ_T ∫_T (σ* − σ_h) : C⁻¹ : (σ* − σ_h))
  double contact = 0;   // the contact part, sqrt of the face terms' sum (0 without contact rows)
  double friction = 0;  // the friction part of `contact`, sqrt of its terms' sum
  // η / ‖u_h‖, ‖u_h‖ = sqrt(2 · strain_energy): the estimated relative energy error; 0 when u_h = 0.
  double relative = 0;
  // The estimated relative error of the contact force, (P_h − P)/P ≈ relative² (docs/estimate.md,
  // "The contact force"): for a frictionless scene driven by prescribed displacements alone, whose
  // energy is then homogeneous in the push and P its derivative, on linear elements; nullopt
  // otherwise (force loads, friction, quadratic elements).
  std::optional<double> force_relative;
  Eigen::VectorXd indicator;  // η_T per element (sqrt of energy), n_elements; Σ η_T² = η²
  // The largest η_T of the whole mesh (a distributed run's indicator holds one rank's elements).
  double max_indicator = 0;
  double seconds = 0;  // the estimate's own time
};

// The estimate of a solution: `u` the QP's free DOFs, `lambda` one multiplier per contact row
// (empty: no contact terms), `friction` each row's friction (nullptr without friction).
ErrorEstimate estimate_error(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& u,
                             const Eigen::VectorXd& lambda, const FrictionFields* friction = nullptr);

// The strain energy alone (ErrorEstimate::strain_energy), for a run whose estimate is turned off.
double strain_energy(const Model& model, const Eigen::VectorXd& u);

// The energy norm of u_coarse − u_fine, sqrt(dᵀ K d), for two solutions of one scene on nested
// meshes (every element of `fine` inside one of `coarse`, as a scene's `refinements` make them):
// u_coarse is interpolated at the fine mesh's nodes (its element located, the isoparametric map
// inverted by Newton's method), d is the difference at the fine model's free DOFs and K =
// fine_qp.K (at prescribed DOFs both solutions take the scene's values). The true error of the
// coarse solution, up to the fine one's own (docs/estimate.md). u_coarse and u_fine are the
// free DOFs of each; the scene may not rotate DOF frames (std::invalid_argument). With several
// bodies each fine node is located in its own body's coarse elements (the bodies in the same
// order in both models).
double energy_distance(const Model& coarse, const Eigen::VectorXd& u_coarse, const Model& fine,
                       const QuadraticProgram& fine_qp, const Eigen::VectorXd& u_fine);

}  // namespace contactqp
