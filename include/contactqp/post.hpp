// Post-processing of a solution: contact pressure, total force, the contact zone's size (a
// half-width b in 2D, a radius a and an area in 3D), and the comparison with the closed forms:
// Hertz for a cylinder (2D) or a sphere (3D) on a plane or another one, Boussinesq for a rigid
// flat punch (3D).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "contactqp/model.hpp"

namespace contactqp {

struct ContactProfilePoint {
  // 2D: position along the obstacle surface (length), see surface_coordinate in contact.hpp;
  // 3D: distance r from the contact centre, across the obstacle normal there (length).
  double s = 0;
  double pressure = 0;  // λ_i / (w_i · thickness) (2D), λ_i / w_i (3D): force per area, compression positive
  double force = 0;     // λ_i, the nodal contact force (for the model's thickness)
  int node = -1;
  int obstacle = -1;
  int row = -1;  // the constraint row (−1 for a pair's face-side point)
};

// Cattaneo–Mindlin (docs/friction.md): normal force P first, then a tangential force Q < μP,
// for two cylinders (2D, per length) or two spheres (3D), or one on a rigid plane. Hertz's b
// (a) and p0 for P; the stick zone c = b sqrt(1 − Q/(μP)) (2D), a (1 − Q/(μP))^(1/3) (3D); the
// traction along Q, q = μ p0 sqrt(1 − x²/b²) in the slip zone c ≤ |x| ≤ b and
// μ p0 [sqrt(1 − x²/b²) − (c/b) sqrt(1 − x²/c²)] in the stick zone. Exact for Dundurs' β = 0
// (bodies of one material); β is reported beside it.
struct MindlinComparison {
  int dim = 2;
  double coefficient = 0;       // μ
  double normal_force = 0;      // P (2D: per length)
  double tangential_force = 0;  // Q, the friction resultant's length (same units)
  double load_ratio = 0;        // Q/(μP)
  double dundurs_beta = 0;  // β = [G1(1 − 2ν2) − G2(1 − 2ν1)] / [2G1(1 − ν2) + 2G2(1 − ν1)], body 1 the node side
  double half_width = 0;    // Hertz's b (2D) or a (3D) for P
  double max_pressure = 0;  // Hertz's p0
  double stick_size = 0;    // Mindlin's c (0 at full sliding, Q ≥ μP)
  double stick_size_computed = 0;
  double error_stick_size = 0;  // (c_h − c)/c, or /b (/a) when c = 0
  double error_l2 = 0;          // ‖q_h − q‖_L2 / ‖q‖_L2 over the contact zone, q_h the traction along Q
  // The tangential displacement of distant points that slip adds to a stuck contact's at the
  // same Q: δ_t(Q) − Q dδ_t/dQ(0). 3D: δ_t = (3μP/(16a)) C [1 − (1 − Q/(μP))^(2/3)], C =
  // (2 − ν1)/G1 + (2 − ν2)/G2; 2D: (2/(π E*)) [Q/2 − μP (c/b)² ln(b/c)] (finite where δ_t is not).
  double slip_displacement = 0;
};

// A symmetric model (body.symmetry) stands for symmetry_copies() mirror images of itself. The
// sum over the images of a vector (a force) keeps its components along the cuts, times the
// copies, and loses those across them (the 3D quarter: along z only; the half y ≥ 0: x and z);
// their mean point (a centre) loses the components across the cuts. Unchanged without symmetry.
Eigen::Vector3d whole_body_sum(const Model& model, const Eigen::Vector3d& vector);
Eigen::Vector3d mirror_mean(const Model& model, const Eigen::Vector3d& point);
double mirror_copies(const Model& model);

// Mindlin's traction along Q at distance x from the centre (0 beyond b or a).
double mindlin_traction(const MindlinComparison& mindlin, double x);

// The friction of one contact zone (an obstacle's or a pair's), for the whole body (doubled by a
// 2D symmetry plane, four times a 3D quarter's).
struct FrictionZone {
  Eigen::Vector3d resultant = Eigen::Vector3d::Zero();  // Σ friction forces on the (node-side) body (global axes)
  double tangential_force = 0;                          // |resultant|
  int stick_nodes = 0, slip_nodes = 0;                  // loaded rows in each state
  // The stick zone's size from its nodes' tributaries: 2D its half-width, Σ w_i / 2; 3D its
  // radius sqrt(Σ w_i / π) (whole body).
  double stick_size = 0;
  std::optional<MindlinComparison> mindlin;  // Coulomb, two round bodies (or one on a plane) with Hertz
};

// Friction at every contact row of a solution with λ_T (docs/friction.md).
struct FrictionFields {
  // The friction force on the row's node: −Σ_k λ_T,k t_k (global axes, for the thickness); a
  // pair's face nodes carry its reaction.
  std::vector<Eigen::Vector3d> force;
  std::vector<Eigen::Vector3d> traction;  // force over the tributary (a 6-node face's vertex: its mid-sides' mean)
  std::vector<Eigen::Vector3d> slip;      // Σ_k (T u − offset)_k t_k: this step's relative tangential displacement
  std::vector<int> state;                 // 0 gap (λ_N = 0), 1 stick, 2 slip (‖λ_T‖ on its bound)
  std::vector<double> bound;              // Tresca's s·w_i, Coulomb's μ_i λ_N,i
};
FrictionFields friction_fields(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& u,
                               const Eigen::VectorXd& lambda, const Eigen::VectorXd& lambda_t);

// The contact on one obstacle.
struct ObstacleContact {
  int obstacle = -1;
  std::vector<ContactProfilePoint> profile;  // its candidates, sorted by s (x ≥ 0 only with symmetry)
  // Σ λ_i for the whole body: doubled when a symmetry plane halves the 2D model, four times
  // the 3D quarter model's (force).
  double total_force = 0;
  double line_load = 0;  // 2D: total_force / thickness (force per length); 3D: total_force
  // Σ λ_i n_i: the obstacle's resultant force on the body (global axes; for the whole body
  // with symmetry). Its length is Hertz's P; on a curved obstacle it is below total_force.
  Eigen::Vector3d resultant = Eigen::Vector3d::Zero();
  // 2D: 2·sqrt(Σλ(s − s̄)² / Σλ): equals b for a Hertz profile and, unlike the last loaded
  // node, does not jump by ±h/2 from mesh to mesh. 0 in 3D.
  double half_width = 0;
  double half_width_last_node = 0;  // 2D: |s − s̄| of the farthest node carrying force
  double centre = 0;                // 2D: s̄, the centre of pressure (0 with symmetry)
  // 3D: the moment estimate a = sqrt(5/2 · Σλ r² / Σλ) (exact for a Hertz pressure, whose
  // mean r² over the disc is 2a²/5), the r of the farthest node carrying force, the loaded area
  // (Σ w_i over the nodes carrying force, for the whole body) and the centre of pressure.
  double contact_radius = 0;
  double contact_radius_last_node = 0;
  double contact_area = 0;
  Eigen::Vector3d centre_point = Eigen::Vector3d::Zero();
  double max_pressure = 0;
  int contact_nodes = 0;                 // candidates carrying force (λ_i > 1e-8 · max λ)
  std::optional<FrictionZone> friction;  // with friction
};

struct ContactSummary {
  std::vector<ContactProfilePoint> profile;  // every candidate, sorted by obstacle, then s
  std::vector<ObstacleContact> obstacles;    // one per obstacle of the scene, in scene order
  double total_force = 0;                    // over all obstacles (force)
  double line_load = 0;                      // total_force / thickness
  // The zone's shape on the obstacle that carries the largest force (the only one, usually).
  int main_obstacle = 0;
  double half_width = 0;
  double half_width_last_node = 0;
  double centre = 0;
  double contact_radius = 0;
  double contact_radius_last_node = 0;
  double contact_area = 0;
  double max_pressure = 0;  // over all obstacles
  int contact_nodes = 0;    // over all obstacles
  // With friction: the tangential force over all obstacles (|Σ resultants|), and the stick
  // zone of the obstacle carrying the largest force.
  double tangential_force = 0;
  double stick_size = 0;
  // Boundary nodes outside the candidate set that end up inside an obstacle: a sign that
  // contact.max_gap was too small.
  int penetrating_non_candidates = 0;
  double max_non_candidate_penetration = 0;  // (length)
};

// The contact pressure at each constraint row's node: λ_i / (w_i · thickness) (2D) or λ_i / w_i
// (3D), w_i the candidate's tributary. Where w_i is 0 — a vertex of a 6-node face, whose
// consistent weight vanishes — the mean pressure of the mid-side nodes beside it on the contact
// boundary's faces (rows of the same obstacle).
std::vector<double> nodal_pressures(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& lambda);

ContactSummary summarize_contact(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& u,
                                 const Eigen::VectorXd& lambda);
// The same in parts, for a model in pieces (src/distributed/): the summary of the rows (from λ
// and the candidates alone; the penetration counts left 0), and the count of the boundary nodes
// `nodes` outside the candidate set that entered an obstacle by more than `tolerance`, added to
// `summary` (displacement: full_displacement() of the model).
ContactSummary summarize_contact_rows(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& lambda);
void count_penetrating(const Model& model, const Eigen::VectorXd& displacement, const std::vector<int>& nodes,
                       double tolerance, ContactSummary& summary);

struct HertzComparison {
  int dim = 2;  // 2: two cylinders (b, per length); 3: two spheres (a)
  // The radius of relative curvature, 1/R = 1/R_body + 1/R_obstacle, and where it came from:
  // "body.radius" (half disc or hemisphere on a plane), "obstacle.radius" (a rigid circle or
  // sphere into a flat body), "body.radius and obstacle.radius", "fitted" (a mesh body: a
  // circle or sphere through the nodes in contact) or "fitted and obstacle.radius".
  double radius = 0;
  std::string radius_source;
  double effective_modulus = 0;     // E* = E/(1 − ν²) in plane strain and solid, E in plane stress
  double force = 0;                 // P: 2D per length, 3D the whole force
  double half_width = 0;            // 2D: b = sqrt(4 P R / (π E*)) for the computed line load P
  double contact_radius = 0;        // 3D: a = (3 P R / (4 E*))^(1/3) for the computed force P
  double max_pressure = 0;          // p0 = 2P / (π b) (2D), 3P / (2π a²) (3D)
  double error_half_width = 0;      // 2D: (b_computed − b) / b
  double error_contact_radius = 0;  // 3D: (a_computed − a) / a, a_computed the moment estimate
  double error_max_pressure = 0;    // (p_max − p0) / p0
  double error_l2 = 0;              // ‖p_h − p_Hertz‖_L2 / ‖p_Hertz‖_L2 over the contact zone
};

// The contact forces on the nodes (dim·n_nodes, global axes, for the thickness in 2D): an
// obstacle's row pushes its node with λ n; a row between two bodies pushes its node with λ n
// and the other body's face nodes with −λ N_j(ξ) n (action and reaction).
Eigen::VectorXd contact_nodal_forces(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& lambda);

// The contact of one pair of bodies (docs/bodies.md). Forces are for the whole bodies (doubled
// by a 2D symmetry plane, four times a 3D quarter model's), for the thickness in 2D.
struct PairContact {
  int pair = -1;
  std::string node_side, face_side;  // "roller.arc": the side whose nodes carry the rows, and the other
  int node_body = -1, face_body = -1;
  std::string side_rule;                                         // why the nodes are on that side
  std::string rows = "node_to_face";                             // or "mortar" (ContactPair::rows)
  Eigen::Vector3d force_on_node_body = Eigen::Vector3d::Zero();  // the face side's push on the node side
  Eigen::Vector3d force_on_face_body = Eigen::Vector3d::Zero();  // and the reaction
  double action_reaction = 0;  // |F_node + F_face| / max(|F_node|, |F_face|): 0 up to round-off
  double total_force = 0;      // Σ λ_i
  double line_load = 0;        // 2D: |F_node| / thickness; 3D: |F_node|
  // The zone as the node side sees it, measured as for an obstacle (ObstacleContact): s along
  // the tangent of the mean contact normal (2D) or r from the centre of pressure across it (3D).
  double half_width = 0, half_width_last_node = 0, centre = 0;
  double contact_radius = 0, contact_radius_last_node = 0, contact_area = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();  // the mean contact normal, into the node side
  // Node side. 3D: max λ_i / w_i. 2D: the max of the three-node patch averages
  // (λ_{i−1} + λ_i + λ_{i+1}) / (w_{i−1} + w_i + w_{i+1}) along the whole body's profile (a half
  // model's mirrored, its node on the symmetry plane counted with its image): with meshes that
  // do not match, node-to-segment pressures alternate node by node by a few per cent (the rows
  // do not pass the patch test), which the patch average removes (docs/bodies.md).
  double max_pressure = 0;
  double max_nodal_pressure = 0;  // node side: max λ_i / w_i, unsmoothed
  double face_max_pressure = 0;   // face side: max of its nodes' share Σ_i λ_i N_j(ξ_i) over their tributary
  int contact_nodes = 0;
  std::vector<ContactProfilePoint> profile;       // node side, sorted by s (obstacle −1)
  std::vector<ContactProfilePoint> face_profile;  // face side's nodes, sorted by s
  // Small slip: loaded nodes whose deformed closest point lies on a face that shares no node
  // with the face their row was linearised on, and the largest tangential slip of a loaded node.
  int slipped_nodes = 0;
  double max_slip = 0;
  std::optional<HertzComparison> hertz;  // two cylinders (2D) or spheres (3D) when both sides are round or flat
  std::optional<FrictionZone> friction;  // with friction
};
std::vector<PairContact> summarize_pairs(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& u,
                                         const Eigen::VectorXd& lambda);

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
// The friction forces on the nodes (dim·n_nodes, global axes): −λ_T t on a row's node, its
// reaction on a pair's face nodes. Zero without friction.
Eigen::VectorXd friction_nodal_forces(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& lambda_t);

// Mindlin's comparison for one contact zone with Coulomb's coefficient μ: `profile` its rows
// (s along the surface in 2D, `centre` the zone's centre; r from the centre in 3D), `hertz` the
// zone's Hertz comparison, `zone` its friction (resultant and stick size), `body` the node
// side's material and `other` the other side's (nullptr: a rigid obstacle).
MindlinComparison compare_with_mindlin(const Model& model, const FrictionFields& fields,
                                       const std::vector<ContactProfilePoint>& profile, double centre,
                                       const HertzComparison& hertz, double coefficient, const FrictionZone& zone,
                                       const Material& body, const Material* other);

// Adds friction to the summaries: each obstacle's and pair's FrictionZone, the summary's
// tangential force and stick size, and Mindlin's comparison where it applies.
void summarize_friction(const Model& model, const FrictionFields& fields, ContactSummary& contact,
                        std::vector<PairContact>& pairs);

// What a support pushes the body with (a displacement load), or what a rigid surface carries
// and how far it moved (a force load, RigidForceLoad).
struct Reaction {
  std::string load;                                 // the load's field path, e.g. "load[0]"
  std::string boundary;                             // its boundary
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // global axes, the whole body's; z = 0 in 2D
  // A force load: the surface's displacement along each component it ties (the scene's own
  // axes, as the load's value), none along a free one; none at all for a displacement load.
  std::optional<double> displacement[3];
  bool rigid_surface() const { return displacement[0] || displacement[1] || displacement[2]; }
  // A force load with a moment: the surface's displacement above is that of `about`, and it
  // turned by `rotation` (radians) about each axis it turns about, carrying `moment` (the
  // whole body's, about `about`); none about an axis it does not turn about.
  std::optional<double> rotation[3];
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();  // the scene's own axes, like the load's
  Eigen::Vector3d about = Eigen::Vector3d::Zero();   // the scene's own frame
  bool turns() const { return rotation[0] || rotation[1] || rotation[2]; }
};
std::vector<Reaction> reactions(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& u,
                                const Eigen::VectorXd& lambda, const Eigen::VectorXd& lambda_t = Eigen::VectorXd());
// The same with a boundary's nodes given by `nodes_of` (a part of a mesh knows a node lies on a
// boundary whose face is another rank's), λ one per candidate (0 for the rows of other ranks)
// and the friction's nodal forces (friction_nodal_forces(); none when empty). A part's sums are
// its elements' and rows' share: the whole's are their sums over the parts.
std::vector<Reaction> reactions(const Model& model, const Eigen::VectorXd& u, const Eigen::VectorXd& lambda,
                                const std::function<std::vector<int>(const std::string&)>& nodes_of,
                                const Eigen::VectorXd& friction_forces = Eigen::VectorXd());

// A body that only its contacts hold (Model::free_motions): how far it moved as a whole, the
// mean of its displacement over its volume (the L2 projection of u on translations), along each
// of the scene's own axes (as a force load's value) that one of its free motions translates it
// along; none along an axis that a support holds (a symmetry plane, a displacement load). One entry per such body, in body
// order; "body" names a one-body scene's.
struct FloatingBody {
  std::string body;
  std::optional<double> translation[3];
};
std::vector<FloatingBody> floating_bodies(const Model& model, const Eigen::VectorXd& u);

// Nodal stresses (force per area), averaged over the elements sharing each node (weighted by
// their areas or volumes) from each element's stress at that node. In 2D σzz = ν(σxx + σyy)
// in plane strain, 0 in plane stress, and σyz = σxz = 0; with the mixed formulation
// σ = D_dev ε + p (p the element's condensed mean stress) and σzz = p − (2μ/3) tr ε. In 3D all
// six components from σ = D ε. von Mises from all of them.
struct NodalStress {
  Eigen::VectorXd xx, yy, xy, zz, yz, xz, von_mises;  // n_nodes each
};
NodalStress nodal_stresses(const Model& model, const Eigen::VectorXd& displacement);  // full_displacement()

// The same in two steps, for a mesh in pieces (src/distributed/ adds the sums of the ranks that
// share a node before dividing): Σ over a node's elements of measure × the element's stress
// there (rows σxx, σyy, σxy, σzz, σyz, σxz) and Σ of the measures.
struct StressSums {
  Eigen::MatrixXd sum;     // 6 × n_nodes
  Eigen::VectorXd weight;  // n_nodes
};
StressSums stress_sums(const Model& model, const Eigen::VectorXd& displacement);
NodalStress nodal_stresses(const StressSums& sums, int dim);

// Boussinesq's rigid flat circular punch of radius a pressed by δ into a half-space (3D):
// P = 2 a E* δ and p(r) = P / (2π a sqrt(a² − r²)). δ is the approach the scene prescribes:
// the displacement loads' push along the punch axis (one value for all of them).
struct PunchComparison {
  double radius = 0;             // a (length)
  double approach = 0;           // δ (length)
  double effective_modulus = 0;  // E* = E/(1 − ν²)
  double force = 0;              // Boussinesq's P = 2 a E* δ
  double error_force = 0;        // (P_computed − P) / P
  // max over the loaded nodes with r ≤ 0.8a of |p(r)·2πa·sqrt(a² − r²)/P_computed − 1|: how far
  // the pressure's shape is from Boussinesq's, away from the singular rim
  double shape_error = 0;
};

// The comparison for a scene whose obstacle carrying the most force is a punch; nullopt when
// it is not one, or no single approach δ follows from the loads.
std::optional<PunchComparison> compare_with_boussinesq(const Model& model, const ContactSummary& contact);

// Hertz's pressure at distance x from the centre of contact: p0 sqrt(1 − x²/b²), 0 outside
// (3D: at distance r, with the contact radius a for b).
double hertz_pressure(const HertzComparison& hertz, double x);

// The computed pressure of a profile (sorted by s) at s: linear between its points, zero beyond
// its first and last point.
double interpolated_pressure(const std::vector<ContactProfilePoint>& profile, double s);

}  // namespace contactqp
