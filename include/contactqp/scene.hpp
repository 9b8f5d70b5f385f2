// A scene: what one contact problem requires, and nothing more, read from a JSON file.
//
//   {
//     "model": "plane_strain",
//     "material": {"E": 1.0, "nu": 0.3},
//     "body": {"shape": "half_disc", "radius": 1.0, "symmetry": true,
//              "mesh": {"size": 0.1, "contact_size": 0.002}},
//     "load": {"type": "displacement", "boundary": "top", "value": [0.0, -0.01]},
//     "obstacle": {"type": "plane", "point": [0.0, 0.0], "normal": [0.0, 1.0]},
//     "solver": {"backend": "uzawa", "tol": 1e-8}
//   }
//
// Bodies may also be rectangles or Gmsh files, loads forces, obstacles circles and profiles,
// and a transform may rotate the whole scene (docs/scenes.md). With "model": "solid" the
// scene is 3D: every vector has three components, the generated bodies are a hemisphere and a
// box, and the obstacles planes, spheres, cylinders and flat circular punches.
//
// Every key is checked: an unknown key is an error naming it (with the nearest valid key as
// a hint), a missing required key or a value of the wrong type or range is an error naming
// the field and the value. The README lists every key with its default.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "contactqp/backends/uzawa.hpp"
#include "contactqp/qp.hpp"

namespace contactqp {

// The elastic model, and with it the dimension: plane strain and plane stress are 2D (forces
// per the body's thickness), solid is 3D linear elasticity.
enum class ElasticModel { PlaneStrain, PlaneStress, Solid };
using PlaneModel = ElasticModel;    // its name when only the 2D models existed
int dimension(ElasticModel model);  // 2 or 3

// How the strain energy is discretised (body.formulation). Displacement: the standard
// displacement formulation. Mixed: 6-node triangles with an element-wise constant mean stress
// condensed out per element (P2–P0), which does not lock as ν → 0.5 (plane strain only;
// docs/incompressible.md).
enum class Formulation { Displacement, Mixed };

struct Material {
  double E = 0;   // Young's modulus (force per area), > 0
  double nu = 0;  // Poisson's ratio, in (−1, 0.5)
};

struct MeshSpec {
  double size = 0;          // element size far from the contact zone (length), > 0
  double contact_size = 0;  // element size along the candidate contact zone (length), in (0, size]
  double grading = 0.1;     // growth of the element size per unit distance from the contact zone, in (0, 1]
  int order =
      1;  // 1: linear (3-node triangles, 4-node tetrahedra), 2: quadratic (6-, 10-node); 0 for a mesh file: its elements decide
  double size_factor = 1;  // .geo files only: multiplies Gmsh's Mesh.MeshSizeFactor (all sizes), > 0
  int refinements =
      0;  // half_disc, hemisphere: Gmsh meshes 2^n times larger sizes, each element then split in 4 (8), n times
  // Generated shapes: when set, the element size wanted at each point x of the body, in its own
  // frame (as "body" describes it: before a transform, "mirror" and "offset") and in lengths,
  // in place of size, contact_size and grading; refinements are then not applied (Gmsh meshes at
  // these sizes). Not a scene key: an adaptive run (AdaptSpec) sets it from its last cycle.
  std::function<double(const Eigen::Vector3d& x)> size_field;
};

struct BodySpec {
  // 2D: "half_disc": the lower half of the disc of radius R centred at (0, R);
  //     "rectangle": x ∈ [−width/2, width/2], y ∈ [0, height].
  // 3D: "hemisphere": the lower half of the ball of radius R centred at (0, 0, R), flat top z = R;
  //     "box": x ∈ [−width/2, width/2], y ∈ [−depth/2, depth/2], z ∈ [0, height].
  // "mesh": a Gmsh .msh (4.1 or 2.2) or .geo file, boundaries named by physical groups.
  std::string shape;
  double radius = 0;             // half_disc, hemisphere: R (length), > 0
  double width = 0, height = 0;  // rectangle, box (length), > 0
  double depth = 0;              // box: the extent along y (length), > 0
  std::string file;              // mesh: the file, resolved against the scene file's directory
  // 2D: model only x ≥ 0, with u_x = 0 on x = 0 (boundary "symmetry"); 3D: only the quarter
  // x ≥ 0, y ≥ 0, with u_x = 0 on x = 0 (boundary "symmetry_x") and u_y = 0 on y = 0 ("symmetry_y").
  bool symmetry = false;
  // 3D, with symmetry: which of the two planes cut the body. "symmetry": "y" keeps only y = 0
  // (the half y ≥ 0: the plane that survives a load along x), "x" only x = 0; true both.
  bool symmetry_x = true, symmetry_y = true;
  double thickness = 1.0;  // 2D: out-of-plane thickness (length); forces and K are per this thickness
  Formulation formulation = Formulation::Displacement;  // "displacement" or "mixed"
  MeshSpec mesh;                                        // generated shapes; for a .geo file only order and size_factor
};

// The loads, one type per kind. Vectors have dim components, z = 0 in 2D.
struct DisplacementLoad {  // a prescribed displacement of a named boundary
  std::string boundary;
  // Prescribed components (length), dim of them; an absent component (JSON null) is left free.
  std::optional<double> value[3];
};
struct TractionLoad {  // a force per area on a named boundary
  std::string boundary;
  Eigen::Vector3d traction = Eigen::Vector3d::Zero();
};
struct PressureLoad {  // a normal pressure on a named boundary
  std::string boundary;
  double pressure = 0;  // force per area, positive pushes into the body
};
struct GravityLoad {   // density × g on the body, or on a region of a mesh body
  double density = 0;  // mass per volume, > 0
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  std::string region;  // a named region of a mesh body; "" for the whole body
};
// A resultant force on a boundary that moves as one rigid surface (docs/scene.md, "Force on a
// rigid surface"): along each given component the boundary's nodes share one unknown
// displacement, and the surface carries that component of the force; a null component leaves
// each node free, as a displacement load's null does. The force is the whole body's (its
// mirror images included, as the report's contact force counts them), for the thickness in 2D.
// Components stay along the scene's own axes under its transform, as a displacement's do.
// A moment (docs/scenes.md, "Moment on a rigid surface"): about each given axis the surface also
// turns, by one unknown angle, and carries that component of the moment about `about`; a null
// component keeps it from turning about that axis, as a surface without a moment is kept.
struct RigidForceLoad {
  std::string boundary;
  std::optional<double> value[3];
  std::optional<double> moment[3];       // about the scene's own axes; 2D: about z only (moment[2])
  std::optional<Eigen::Vector3d> about;  // the moment's point (scene frame); the boundary's centroid when absent
  bool turns() const { return moment[0] || moment[1] || moment[2]; }
};
struct PointLoad {                    // a force (for the thickness) at the node nearest a point
  std::optional<Eigen::Vector3d> at;  // the location (the nearest node takes the force)
  std::string point;                  // a named physical point of a mesh body instead of `at`
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
};

struct LoadSpec {
  std::string path;  // the load's field path in the scene ("load", "load[2]"), for messages
  std::string name;  // "name": what load steps call it (scene.steps); "" for a load acting in full in every step
  std::variant<DisplacementLoad, TractionLoad, PressureLoad, GravityLoad, PointLoad, RigidForceLoad> kind;

  std::string type() const;  // "displacement", "traction", "pressure", "gravity", "point", "force"
  template <class Kind>
  const Kind* as() const {
    return std::get_if<Kind>(&kind);
  }
  template <class Kind>
  Kind* as() {
    return std::get_if<Kind>(&kind);
  }
  template <class Kind>
  bool is() const {
    return std::holds_alternative<Kind>(kind);
  }
  bool is_force() const { return !is<DisplacementLoad>(); }
  // The boundary a displacement, traction, pressure or rigid force acts on; nullptr for gravity and a point force.
  const std::string* boundary() const;
  std::string* boundary();
};

// The rigid obstacles, one type per kind. Points and directions have z = 0 in 2D. Every
// normal or axis is a unit vector (normalised on read).
struct PlaneObstacle {  // 2D, 3D: the half-space {x : (x − point)·normal ≥ 0} is free
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();  // towards the body
};
struct CircleObstacle {  // 2D: a rigid cylinder seen in section; the body stays outside it
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0;  // (length), > 0
};
struct ProfileObstacle {                // 2D: a polyline through `points` (its end segments extended)
  std::vector<Eigen::Vector3d> points;  // ≥ 2, distinct consecutive points
  bool body_on_left = true;             // the body lies left of the path from the first point to the last
};
struct SphereObstacle {  // 3D: a rigid ball; the body stays outside it
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0;  // (length), > 0
};
struct CylinderObstacle {                           // 3D: a rigid infinite cylinder; the body stays outside it
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // a point of its axis
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // unit
  double radius = 0;                                // (length), > 0
};
// 3D: a rigid flat-ended circular punch (Boussinesq's problem): the disc of `radius` centred at
// `center`, normal `axis` towards the body, with the punch's body behind it (its rim a sharp edge).
struct PunchObstacle {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit, towards the body
  double radius = 0;                                // a (length), > 0
};

// Friction on a contact boundary, an obstacle or a pair ("friction": {"coefficient": μ} or
// {"threshold": s}; docs/friction.md). One law per scene.
struct FrictionSpec {
  std::string path;                     // its field path ("contact.friction"), for messages
  FrictionLaw law = FrictionLaw::None;  // Coulomb (a coefficient) or Tresca (a threshold)
  double coefficient = 0;               // Coulomb: μ ≥ 0, ‖λ_T,i‖ ≤ μ λ_N,i
  double threshold = 0;                 // Tresca: s ≥ 0 (force per area), ‖λ_T,i‖ ≤ s·w_i
};

struct ObstacleSpec {
  std::string path;  // field path ("obstacle", "obstacle[1]"), for messages
  std::variant<PlaneObstacle, CircleObstacle, ProfileObstacle, SphereObstacle, CylinderObstacle, PunchObstacle> shape;
  std::optional<FrictionSpec> friction = std::nullopt;  // on the rows against this obstacle; none: frictionless

  std::string type() const;  // "plane", "circle", "profile", "sphere", "cylinder", "punch"
  template <class Kind>
  const Kind* as() const {
    return std::get_if<Kind>(&shape);
  }
  template <class Kind>
  bool is() const {
    return std::holds_alternative<Kind>(shape);
  }
};

struct ContactSpec {
  std::string boundary;           // boundary that may touch; default: the shape's (half_disc "arc", rectangle "bottom")
  std::optional<double> max_gap;  // candidates have initial gap ≤ max_gap; default follows from the loads
  std::optional<FrictionSpec> friction;  // on every row of the boundary (then no obstacle has its own)
};

// A rigid rotation of the whole scene about the origin: the body, the load vectors and the
// obstacles as written are turned by rotate_degrees (counter-clockwise about `axis`: always z
// in 2D, given in 3D).
struct TransformSpec {
  double rotate_degrees = 0;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit
  Eigen::Matrix3d rotation() const;                 // exact for multiples of 90° about a coordinate axis
  bool is_identity() const { return rotate_degrees == 0; }
};

// Scenes with several elastic bodies ("bodies": [...], docs/bodies.md). Each body is meshed in
// its own frame, as a one-body scene would mesh it, then placed: mirrored (y → −y in 2D,
// z → −z in 3D, so that a half disc or a hemisphere faces upwards) and then shifted by `offset`.
// Loads, points and the obstacles are written in the scene's (global) frame.
struct BodyPlacement {
  bool mirror = false;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // dim components, z = 0 in 2D
  Eigen::Vector3d to_global(const Eigen::Vector3d& local, int dim) const;
  Eigen::Vector3d to_local(const Eigen::Vector3d& global, int dim) const;
  Eigen::Vector3d direction_to_local(const Eigen::Vector3d& direction, int dim) const;  // mirror only
};

struct SceneBody {
  std::string name;  // unique; pairs name its boundaries "name.boundary"
  std::string path;  // "bodies[1]", for messages
  Material material;
  BodySpec body;
  std::vector<LoadSpec> loads;  // its own; boundaries are the body's own names
  BodyPlacement placement;
};

// A pair of boundaries of two bodies that may touch: {"pair": ["roller.surface", "block.top"]}.
// How a pair's rows tie the node side to the face side (docs/bodies.md, "Mortar rows").
enum class PairRows {
  NodeToFace,  // each node against the closest point of one face (node-to-segment in 2D)
  Mortar,      // each node's share of its side against the faces it overlaps (dual mortar)
};

struct ContactPair {
  std::string path;  // "contact[0]"
  int body[2] = {-1, -1};
  std::string boundary[2];
  PairRows rows = PairRows::NodeToFace;
  std::optional<double> max_gap;         // the pair's candidate distance; default follows from the loads
  std::optional<FrictionSpec> friction;  // between the two sides; none: frictionless
};

// A boundary of one body that may touch the rigid obstacles: {"boundary": "block.bottom"}.
struct ObstacleContactSpec {
  std::string path;
  int body = -1;
  std::string boundary;
  std::optional<double> max_gap;
  std::optional<FrictionSpec> friction;  // on the boundary's rows against every obstacle
};

// One load step ("steps": [{"factors": {"push": 1}}, ...]; docs/friction.md): the factors of the
// named loads at the end of the step, totals rather than increments. A load a step does not name
// keeps its factor from the step before; a named load starts at 0, an unnamed one acts in full
// in every step.
struct LoadStep {
  std::string path;                                     // "steps[1]", for messages
  std::vector<std::pair<std::string, double>> factors;  // (load name, factor) as written
};

// "adapt": {"target": 0.01}: solve, estimate the error, remesh the generated bodies with sizes
// from the error indicators, and solve again, until the estimated relative energy error
// η / sqrt(2E) is at most `target` (docs/adaptive.md). A run that stops short of it (the DOF
// budget or the cycles spent) ends with the last cycle's answer and says what it reached.
struct AdaptSpec {
  double target = 0;             // η / sqrt(2E) wanted, in (0, 1)
  long long max_dofs = 1000000;  // no cycle is run on a mesh expected to have more DOFs, > 0
  int max_cycles = 12;           // solves in all, the first on the scene's own mesh included, ≥ 1
};

struct Scene {
  std::string source;  // file the scene was read from ("" for a string)
  PlaneModel model = PlaneModel::PlaneStrain;
  Material material;
  BodySpec body;
  std::vector<LoadSpec> loads;
  std::vector<ObstacleSpec> obstacles;
  ContactSpec contact;
  TransformSpec transform;
  SolveOptions solver;  // from the "solver" section; the command line overrides it
  // A scene with a "bodies" list: every body, the pairs that may touch and the boundaries that
  // may touch the obstacles. Empty for a one-body scene ("body"), which the fields above hold;
  // with bodies, material, body and loads above are bodies[0]'s (for what reads one body's).
  std::vector<SceneBody> bodies;
  std::vector<ContactPair> pairs;
  std::vector<ObstacleContactSpec> obstacle_contacts;
  // Load steps, solved in order, each from the state the last one left (quasi-static,
  // incremental). Empty: one step with every load in full.
  std::vector<LoadStep> steps;
  // The energy-error estimate after the solve (docs/estimate.md): the scene's "estimate", the
  // command line's --no-estimate.
  bool estimate = true;
  // An adaptive run (docs/adaptive.md): the scene's "adapt", the command line's --adapt.
  std::optional<AdaptSpec> adapt;

  int dim() const { return dimension(model); }
  // The scene's friction law: None when no boundary, obstacle or pair has friction.
  FrictionLaw friction_law() const;
};

// The factor of each load at each step: factors[k][l] for step k and load l, the loads in the
// order of scene.loads followed by each body's (scene.bodies order). One step of factors 1 for
// a scene without steps.
std::vector<std::vector<double>> load_factors(const Scene& scene);

// Parses and validates a scene. Throws InputError naming the field (or the file) on any
// problem. `source` names the text in error messages; a mesh file named by the scene is
// resolved against the directory of `source`.
Scene parse_scene(const std::string& json_text, const std::string& source = "scene");
Scene load_scene(const std::string& path);  // InputError("path", ...) when unreadable

std::string to_string(ElasticModel model);       // "plane_strain", "plane_stress", "solid"
std::string to_string(Formulation formulation);  // "displacement", "mixed"

// "auto", a number (absolute ρ) or a fraction of ρ_max written "0.5x".
UzawaOptions parse_rho(const std::string& text, const std::string& field);

// The boundaries a generated shape has, e.g. {"arc", "top", "symmetry"} for a symmetric
// half disc, {"surface", "top", "symmetry_x", "symmetry_y"} for a symmetric hemisphere; a
// scene may name only these. Empty for a mesh body: its physical groups decide,
// and build_model() checks the names.
std::vector<std::string> boundary_names(const BodySpec& body);

// The boundaries a symmetric body is cut by, and the displacement component each holds at
// zero: {"symmetry"} (x = 0, u_x) in 2D; {"symmetry_x", "symmetry_y"} (x = 0, u_x and y = 0, u_y)
// in 3D, or the one body.symmetry names. Empty without symmetry.
std::vector<std::string> symmetry_boundaries(const BodySpec& body, int dim);
// Whether a symmetry plane cuts the body at x_component = 0 (0: x, 1: y; only x in 2D).
bool symmetric_about(const BodySpec& body, int component, int dim);
// How many mirror copies of the modelled part make the whole body: 2 per plane.
int symmetry_copies(const BodySpec& body, int dim);
// body.symmetry as a scene writes it: "true", "false", or the one plane, "x" or "y".
std::string symmetry_name(const BodySpec& body);
int symmetry_component(const std::string& boundary);  // 0 for "symmetry" and "symmetry_x", 1 for "symmetry_y"

// The same scene seen after its transform: obstacles and load vectors rotated, the transform
// reset to the identity. (The body's mesh is rotated by build_model.)
Scene rotated(const Scene& scene);

}  // namespace contactqp
