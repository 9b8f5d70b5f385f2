// Post-processing of a solution: contact pressure, total force, contact half-width, and the
// comparison with Hertz's analytic solution for a cylinder on a rigid plane.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "contactqp/model.hpp"

namespace contactqp {

struct ContactProfilePoint {
  double s = 0;         // position along the obstacle surface (length), see surface_coordinate in contact.hpp
  double pressure = 0;  // λ_i / (w_i · thickness): force per area, compression positive
  double force = 0;     // λ_i, the nodal contact force (for the model's thickness)
  int node = -1;
  int obstacle = -1;
};

// The contact on one obstacle.
struct ObstacleContact {
  int obstacle = -1;
  std::vector<ContactProfilePoint> profile;  // its candidates, sorted by s (x ≥ 0 only with symmetry)
  double total_force = 0;    // Σ λ_i, doubled when a symmetry plane halves the model (force)
  double line_load = 0;      // total_force / thickness (force per length)
  // Σ λ_i n_i: the obstacle's resultant force on the body (global x, y; for the whole body
  // with symmetry). Its length is Hertz's P; on a curved obstacle it is below total_force.
  Eigen::Vector2d resultant = Eigen::Vector2d::Zero();
  // 2·sqrt(Σλ(s − s̄)² / Σλ): equals b for a Hertz profile and, unlike the last loaded node,
  // does not jump by ±h/2 from mesh to mesh.
  double half_width = 0;
  double half_width_last_node = 0;  // |s − s̄| of the farthest node carrying force
  double centre = 0;                // s̄, the centre of pressure (0 with symmetry)
  double max_pressure = 0;
  int contact_nodes = 0;            // candidates carrying force (λ_i > 1e-8 · max λ)
};

struct ContactSummary {
  std::vector<ContactProfilePoint> profile;  // every candidate, sorted by obstacle, then s
  std::vector<ObstacleContact> obstacles;    // one per obstacle of the scene, in scene order
  double total_force = 0;  // over all obstacles (force)
  double line_load = 0;    // total_force / thickness
  // The zone's shape on the obstacle that carries the largest force (the only one, usually).
  int main_obstacle = 0;
  double half_width = 0;
  double half_width_last_node = 0;
  double centre = 0;
  double max_pressure = 0;  // over all obstacles
  int contact_nodes = 0;    // over all obstacles
  // Boundary nodes outside the candidate set that end up inside an obstacle: a sign that
  // contact.max_gap was too small.
  int penetrating_non_candidates = 0;
  double max_non_candidate_penetration = 0;  // (length)
};

ContactSummary summarize_contact(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& u,
                                 const Eigen::VectorXd& lambda);

struct HertzComparison {
  // The radius of relative curvature, 1/R = 1/R_body + 1/R_obstacle, and where it came from:
  // "body.radius" (half disc on a plane), "obstacle.radius" (a rigid circle into a flat
  // rectangle), "body.radius and obstacle.radius", "fitted" (a mesh body: a circle through
  // the nodes in contact) or "fitted and obstacle.radius".
  double radius = 0;
  std::string radius_source;
  double effective_modulus = 0;   // E* = E/(1 − ν²) in plane strain, E in plane stress
  double half_width = 0;          // b = sqrt(4 P R / (π E*)) for the computed line load P
  double max_pressure = 0;        // p0 = 2P / (π b)
  double error_half_width = 0;    // (b_computed − b) / b
  double error_max_pressure = 0;  // (p_max − p0) / p0
  double error_l2 = 0;            // ‖p_h − p_Hertz‖_L2 / ‖p_Hertz‖_L2 over the contact zone
};

// Hertz's solution for the contact on one obstacle, when its two surfaces are curved
// cylinders or a cylinder and a plane with positive relative curvature: a half disc's arc on a
// plane or circle, a flat rectangle side on a circle, a mesh body whose contact nodes lie on
// a circle. Otherwise (a profile obstacle, a flat body on a plane, too few contact nodes)
// nullopt. Valid for b ≪ R and b ≪ the body's size.
std::optional<HertzComparison> compare_with_hertz(const Model& model, const ObstacleContact& contact);

// The comparison for a scene with one obstacle; nullopt with several.
std::optional<HertzComparison> compare_with_hertz(const Model& model, const ContactSummary& contact);

// The force each displacement load exerts on the body through its boundary (global x, y,
// for the thickness): r = K u − f − (contact forces), summed over the boundary's nodes. With
// the contact forces and the force loads it balances: Σ r + Σ λ n + Σ f = 0 (doubled
// consistently when a symmetry plane halves the model, whose own reaction is left out).
struct Reaction {
  std::string load;      // the load's field path, e.g. "load[0]"
  std::string boundary;  // its boundary
  Eigen::Vector2d force = Eigen::Vector2d::Zero();
};
std::vector<Reaction> reactions(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& u,
                                const Eigen::VectorXd& lambda);

// Nodal stresses (force per area), averaged over the elements sharing each node (weighted by
// their areas) from each element's stress at that node. σzz = ν(σxx + σyy) in plane strain,
// 0 in plane stress; with the mixed formulation σ = D_dev ε + p (p the element's condensed
// mean stress) and σzz = p − (2μ/3) tr ε. von Mises from all four.
struct NodalStress {
  Eigen::VectorXd xx, yy, xy, zz, von_mises;  // n_nodes each
};
NodalStress nodal_stresses(const Model& model, const Eigen::VectorXd& displacement);  // full_displacement()

// Hertz's pressure at distance x from the centre of contact: p0 sqrt(1 − x²/b²), 0 outside.
double hertz_pressure(const HertzComparison& hertz, double x);

// The computed pressure of a profile (sorted by s) at s: linear between its points, zero beyond
// its first and last point.
double interpolated_pressure(const std::vector<ContactProfilePoint>& profile, double s);

}  // namespace contactqp
