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
// and a transform may rotate the whole scene (README: "Scene format").
//
// Every key is checked: an unknown key is an error naming it (with the nearest valid key as
// a hint), a missing required key or a value of the wrong type or range is an error naming
// the field and the value. The README lists every key with its default.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "contactqp/qp.hpp"

namespace contactqp {

enum class PlaneModel { PlaneStrain, PlaneStress };

// How the strain energy is discretised (body.formulation). Displacement: the standard
// displacement formulation. Mixed: 6-node triangles with an element-wise constant mean stress
// condensed out per element (P2–P0), which does not lock as ν → 0.5 (plane strain only;
// README: "Nearly incompressible bodies").
enum class Formulation { Displacement, Mixed };

struct Material {
  double E = 0;   // Young's modulus (force per area), > 0
  double nu = 0;  // Poisson's ratio, in (−1, 0.5)
};

struct MeshSpec {
  double size = 0;          // element size far from the contact zone (length), > 0
  double contact_size = 0;  // element size along the candidate contact zone (length), in (0, size]
  double grading = 0.1;     // growth of the element size per unit distance from the contact zone, in (0, 1]
  int order = 1;            // 1: 3-node, 2: 6-node triangles; 0 for a mesh file: its elements decide
  double size_factor = 1;   // .geo files only: multiplies Gmsh's Mesh.MeshSizeFactor (all sizes), > 0
};

struct BodySpec {
  // "half_disc": the lower half of the disc of radius R centred at (0, R);
  // "rectangle": x ∈ [−width/2, width/2], y ∈ [0, height];
  // "mesh": a Gmsh .msh (4.1 or 2.2) or .geo file, boundaries named by physical groups.
  std::string shape;
  double radius = 0;             // half_disc: R (length), > 0
  double width = 0, height = 0;  // rectangle (length), > 0
  std::string file;              // mesh: the file, resolved against the scene file's directory
  bool symmetry = false;   // model only x ≥ 0, with u_x = 0 on x = 0 (boundary "symmetry")
  double thickness = 1.0;  // out-of-plane thickness (length); forces and K are per this thickness
  Formulation formulation = Formulation::Displacement;  // "displacement" or "mixed"
  MeshSpec mesh;           // generated shapes; for a .geo file only order and size_factor
};

struct LoadSpec {
  // "displacement": prescribed displacement of a named boundary;
  // "traction": a force per area on a named boundary; "pressure": a normal pressure on it;
  // "gravity": density × g on the body (or a region); "point": a force at the node nearest a point.
  std::string type;
  std::string path;      // the load's field path in the scene ("load", "load[2]"), for messages
  std::string boundary;  // displacement, traction, pressure: a boundary name
  // displacement: prescribed components (length); an absent component (JSON null) is left free.
  std::optional<double> value[2];
  // traction: force per area; gravity: the acceleration g; point: the force (for the thickness).
  Eigen::Vector2d vector = Eigen::Vector2d::Zero();
  double pressure = 0;  // pressure: force per area, positive pushes into the body
  double density = 0;   // gravity: mass per volume, > 0
  std::string region;   // gravity: a named region of a mesh body; "" for the whole body
  std::optional<Eigen::Vector2d> at;  // point: the location (the nearest node takes the force)
  std::string point;                  // point: a named physical point of a mesh body instead of `at`

  bool is_force() const { return type != "displacement"; }
};

struct ObstacleSpec {
  // "plane": the half-space {x : (x − point)·normal ≥ 0} is free;
  // "circle": a rigid cylinder; the body stays outside it;
  // "profile": a polyline through `points` (its end segments extended), the body on `body_side`.
  std::string type;
  std::string path;        // field path ("obstacle", "obstacle[1]"), for messages
  Eigen::Vector2d point = Eigen::Vector2d::Zero();   // plane: a point of the surface
  Eigen::Vector2d normal = Eigen::Vector2d::UnitY();  // plane: unit normal towards the body (normalised on read)
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  // circle
  double radius = 0;                                  // circle (length), > 0
  std::vector<Eigen::Vector2d> points;               // profile: ≥ 2 distinct consecutive points
  bool body_on_left = true;  // profile: the body lies left of the path from the first point to the last
};

struct ContactSpec {
  std::string boundary;           // boundary that may touch; default: the shape's (half_disc "arc", rectangle "bottom")
  std::optional<double> max_gap;  // candidates have initial gap ≤ max_gap; default follows from the loads
};

// A rigid rotation of the whole scene about the origin: the body, the load vectors and the
// obstacles as written are turned by rotate_degrees (counter-clockwise).
struct TransformSpec {
  double rotate_degrees = 0;
  Eigen::Matrix2d rotation() const;
  bool is_identity() const { return rotate_degrees == 0; }
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
};

// Parses and validates a scene. Throws InputError naming the field (or the file) on any
// problem. `source` names the text in error messages; a mesh file named by the scene is
// resolved against the directory of `source`.
Scene parse_scene(const std::string& json_text, const std::string& source = "scene");
Scene load_scene(const std::string& path);  // InputError("path", ...) when unreadable

std::string to_string(PlaneModel model);
std::string to_string(Formulation formulation);  // "displacement", "mixed"

// "auto", a number (absolute ρ) or a fraction of ρ_max written "0.5x".
UzawaOptions parse_rho(const std::string& text, const std::string& field);

// The boundaries a generated shape has, e.g. {"arc", "top", "symmetry"} for a symmetric
// half disc; a scene may name only these. Empty for a mesh body: its physical groups decide,
// and build_model() checks the names.
std::vector<std::string> boundary_names(const BodySpec& body);

// The same scene seen after its transform: obstacles and load vectors rotated, the transform
// reset to the identity. (The body's mesh is rotated by build_model.)
Scene rotated(const Scene& scene);

}  // namespace contactqp
