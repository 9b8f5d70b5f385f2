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

struct Material {
  double E = 0;   // Young's modulus (force per area), > 0
  double nu = 0;  // Poisson's ratio, in (−1, 0.5)
};

struct MeshSpec {
  double size = 0;          // element size far from the contact zone (length), > 0
  double contact_size = 0;  // element size along the candidate contact zone (length), in (0, size]
  double grading = 0.1;     // growth of the element size per unit distance from the contact zone, in (0, 1]
  int order = 1;            // 1: 3-node triangles, 2: 6-node triangles
};

struct BodySpec {
  std::string shape;       // "half_disc": lower half of the disc of radius R centred at (0, R)
  double radius = 0;       // R (length), > 0
  bool symmetry = false;   // model only x ≥ 0, with u_x = 0 on x = 0
  double thickness = 1.0;  // out-of-plane thickness (length); forces and K are per this thickness
  MeshSpec mesh;
};

struct LoadSpec {
  std::string type;      // "displacement": prescribed displacement of a named boundary
  std::string boundary;  // boundary name, e.g. "top"
  // Prescribed components (length); an absent component (JSON null) is left free.
  std::optional<double> value[2];
};

struct ObstacleSpec {
  std::string type;        // "plane": the half-space {x : (x − point)·normal ≥ 0} is free
  Eigen::Vector2d point;   // a point of the obstacle surface
  Eigen::Vector2d normal;  // unit normal from the obstacle towards the body (normalised on read)
};

struct ContactSpec {
  std::string boundary;           // boundary that may touch; default: the shape's curved boundary
  std::optional<double> max_gap;  // candidates have initial gap ≤ max_gap; default follows from the load
};

struct Scene {
  std::string source;  // file the scene was read from ("" for a string)
  PlaneModel model = PlaneModel::PlaneStrain;
  Material material;
  BodySpec body;
  std::vector<LoadSpec> loads;
  std::vector<ObstacleSpec> obstacles;
  ContactSpec contact;
  SolveOptions solver;  // from the "solver" section; the command line overrides it
};

// Parses and validates a scene. Throws InputError naming the field (or the file) on any
// problem. `source` names the text in error messages.
Scene parse_scene(const std::string& json_text, const std::string& source = "scene");
Scene load_scene(const std::string& path);  // InputError("path", ...) when unreadable

std::string to_string(PlaneModel model);

// "auto", a number (absolute ρ) or a fraction of ρ_max written "0.5x".
UzawaOptions parse_rho(const std::string& text, const std::string& field);

// The boundaries a generated shape has, e.g. {"arc", "top", "symmetry"} for a symmetric
// half disc; a scene may name only these.
std::vector<std::string> boundary_names(const BodySpec& body);

}  // namespace contactqp
