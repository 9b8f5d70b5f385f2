// Reading and validating scene files. Every rule a value must satisfy is checked here, once,
// before any mesh is built, so that bad input fails fast with the field's name.
#include "contactqp/scene.hpp"

#include <algorithm>
#include <cmath>

#include "contactqp/errors.hpp"
#include "readers.hpp"
#include "scene/input_file.hpp"
#include "scene_keys.hpp"

namespace contactqp {
namespace {

using detail::describe;
using detail::JsonObject;
using detail::nearest;
using nlohmann::json;

ContactSpec read_contact(JsonObject contact, const BodySpec& body);

}  // namespace

using detail::one_or_many;
using detail::read_solver;

namespace detail {

Eigen::Vector3d read_vector(const json& value, const std::string& path, int dim) {
  if (!value.is_array() || static_cast<int>(value.size()) != dim)
    throw InputError(path,
                     "= " + describe(value) +
                         (dim == 2 ? ": must be an array of two numbers [x, y]"
                                   : ": must be an array of three numbers [x, y, z] (\"model\": \"solid\" is 3D)"));
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int c = 0; c < dim; ++c) x[c] = as_number(value[c], path + "[" + std::to_string(c) + "]");
  return x;
}

Eigen::Vector3d read_direction(const json& value, const std::string& path, int dim) {
  const Eigen::Vector3d d = read_vector(value, path, dim);
  double length = d.norm();
  // Components near the largest double overflow the plain norm; the scaled one does not.
  if (!std::isfinite(length)) length = d.stableNorm();
  if (!(length > 0)) throw InputError(path, "= " + describe(value) + ": must be a non-zero vector");
  return d / length;
}

void unknown_choice(const std::string& path, const std::string& value, const std::string& what,
                    const std::vector<std::string>& valid) {
  const std::string hint = nearest(value, valid);
  throw InputError(path, "= \"" + value + "\": unknown " + what + "; valid: " + join(valid) +
                             (hint.empty() ? "" : "; did you mean \"" + hint + "\"?"));
}

Material read_material(JsonObject material) {
  Material m;
  const std::string E_path = material.path_of("E"), nu_path = material.path_of("nu");
  m.E = material.number("E");
  require(m.E > 0, E_path, m.E, "must be positive");
  m.nu = material.number("nu");
  require(m.nu > -1 && m.nu < 0.5, nu_path, m.nu, "must lie in (-1, 0.5)");
  // The largest entry of D, E(1 − ν)/((1 + ν)(1 − 2ν)), and the bulk modulus must be numbers.
  const double nu = m.nu, stiffest = m.E / ((1 + nu) * (1 - 2 * nu)) * std::max(1.0, 1 - nu);
  require(std::isfinite(stiffest) && std::isfinite(m.E / (3 * (1 - 2 * nu))), E_path, m.E,
          "overflows double precision in the elasticity matrix with " + nu_path + " = " + format_value(nu) +
              "; use other units");
  material.finish();
  return m;
}

void require_boundary(const std::string& name, const BodySpec& body, const std::string& path) {
  if (body.shape == "mesh") return;  // its physical groups are known once the mesh is read
  const std::vector<std::string> names = boundary_names(body);
  for (const auto& known : names)
    if (name == known) return;
  const std::string hint = nearest(name, names);
  throw InputError(path, "= \"" + name + "\": not a boundary of a " + body.shape +
                             (body.symmetry ? " with symmetry" : "") + "; valid: " + join(names) +
                             (hint.empty() ? "" : "; did you mean \"" + hint + "\"?"));
}

// A section that may be one object or an array of them ("load": {...} or "load": [{...}]).
std::vector<std::pair<const json*, std::string>> one_or_many(const json& value, const std::string& path) {
  std::vector<std::pair<const json*, std::string>> items;
  if (value.is_array()) {
    if (value.empty()) throw InputError(path, "= []: must hold at least one entry");
    for (size_t i = 0; i < value.size(); ++i) items.emplace_back(&value[i], path + "[" + std::to_string(i) + "]");
  } else {
    items.emplace_back(&value, path);
  }
  return items;
}

}  // namespace detail
namespace {

std::string default_contact_boundary(const BodySpec& body, int dim) {
  if (body.shape == "half_disc") return "arc";
  if (body.shape == "rectangle" || body.shape == "box") return "bottom";
  if (body.shape == "hemisphere") return "surface";
  throw InputError("contact.boundary", std::string("is missing: a mesh body needs the name of the ") +
                                           (dim == 2 ? "physical curve" : "physical surface") + " that may touch");
}

ContactSpec read_contact(JsonObject contact, const BodySpec& body) {
  ContactSpec spec;
  if (auto boundary = contact.optional_string("boundary")) {
    spec.boundary = *boundary;
    detail::require_boundary(spec.boundary, body, contact.path_of("boundary"));
  }
  spec.max_gap = contact.optional_number("max_gap");
  if (spec.max_gap) require(*spec.max_gap >= 0, contact.path_of("max_gap"), *spec.max_gap, "must be ≥ 0");
  if (contact.has("friction")) spec.friction = detail::read_friction(contact.object("friction"));
  contact.finish();
  return spec;
}

}  // namespace
namespace detail {

void read_solver(JsonObject solver, SolveOptions& options) {
  if (auto backend = solver.optional_string("backend"))
    options.backend = parse_backend(*backend, solver.path_of("backend"));
  if (auto linear_solver = solver.optional_string("linear_solver"))
    options.linear_solver = parse_linear_solver(*linear_solver, solver.path_of("linear_solver"));
  // PETSc's options database entries, as --petsc-options gives them: kept by library name for
  // whichever part of contactqp uses PETSc (docs/petsc.md).
  if (auto petsc_options = solver.optional_string("petsc_options")) options.library_options["petsc"] = *petsc_options;
  if (auto tol = solver.optional_number("tol")) {
    options.tol = *tol;
    require(*tol > 0 && *tol < 1, solver.path_of("tol"), *tol, "must lie in (0, 1)");
  }
  if (solver.has("rho")) {
    const json& rho = solver.value("rho");
    if (rho.is_number()) {
      UzawaOptions uzawa;
      uzawa.rho_rule = UzawaOptions::RhoRule::Absolute;
      uzawa.rho = detail::as_number(rho, solver.path_of("rho"));
      require(uzawa.rho > 0, solver.path_of("rho"), uzawa.rho, "must be positive");
      options.set(uzawa);
    } else if (rho.is_string()) {
      options.set(parse_rho(rho.get<std::string>(), solver.path_of("rho")));
    } else {
      throw InputError(solver.path_of("rho"),
                       "= " + describe(rho) + ": must be \"auto\", a number, or a fraction of ρ_max such as \"0.5x\"");
    }
  }
  if (auto max_iterations = solver.optional_integer("max_iterations")) {
    options.max_iterations = *max_iterations;
    require(*max_iterations > 0, solver.path_of("max_iterations"), *max_iterations, "must be positive");
  }
  if (solver.has("options")) {
    // Backend options as in --backend-option key=value; the backend checks keys and values.
    const json& entries = solver.value("options");
    const std::string path = solver.path_of("options");
    if (!entries.is_object()) throw InputError(path, "= " + describe(entries) + ": must be an object {\"key\": value}");
    for (const auto& [key, value] : entries.items()) {
      if (value.is_string())
        options.backend_options[key] = value.get<std::string>();
      else if (value.is_number())
        options.backend_options[key] = value.dump();
      else
        throw InputError(path + "." + key, "= " + describe(value) + ": must be a string or a number");
    }
  }
  solver.finish();
}

}  // namespace detail

std::string to_string(ElasticModel model) {
  switch (model) {
    case ElasticModel::PlaneStrain:
      return "plane_strain";
    case ElasticModel::PlaneStress:
      return "plane_stress";
    case ElasticModel::Solid:
      return "solid";
  }
  return "?";
}

int dimension(ElasticModel model) { return model == ElasticModel::Solid ? 3 : 2; }

bool symmetric_about(const BodySpec& body, int component, int dim) {
  if (!body.symmetry || component > dim - 2) return false;
  return dim == 2 || (component == 0 ? body.symmetry_x : body.symmetry_y);
}

std::vector<std::string> symmetry_boundaries(const BodySpec& body, int dim) {
  if (dim == 2) return body.symmetry ? std::vector<std::string>{"symmetry"} : std::vector<std::string>{};
  std::vector<std::string> planes;
  if (symmetric_about(body, 0, dim)) planes.push_back("symmetry_x");
  if (symmetric_about(body, 1, dim)) planes.push_back("symmetry_y");
  return planes;
}

int symmetry_copies(const BodySpec& body, int dim) { return 1 << symmetry_boundaries(body, dim).size(); }

std::string symmetry_name(const BodySpec& body) {
  if (!body.symmetry) return "false";
  if (body.symmetry_x && body.symmetry_y) return "true";
  return body.symmetry_x ? "x" : "y";
}

int symmetry_component(const std::string& boundary) { return boundary == "symmetry_y" ? 1 : 0; }

std::string to_string(Formulation formulation) { return formulation == Formulation::Mixed ? "mixed" : "displacement"; }

std::vector<std::string> boundary_names(const BodySpec& body) {
  std::vector<std::string> names;
  if (body.shape == "half_disc")
    names = {"arc", "top"};
  else if (body.shape == "rectangle")
    names = {"bottom", "right", "top", body.symmetry ? "" : "left"};
  else if (body.shape == "hemisphere")
    names = {"surface", "top"};
  else if (body.shape == "box")
    names = {
        "bottom", "top", symmetric_about(body, 0, 3) ? "" : "left", "right", symmetric_about(body, 1, 3) ? "" : "front",
        "back"};
  names.erase(std::remove(names.begin(), names.end(), ""), names.end());
  if (body.symmetry && body.shape != "mesh") {
    const bool solid = body.shape == "hemisphere" || body.shape == "box";
    for (const std::string& plane : symmetry_boundaries(body, solid ? 3 : 2)) names.push_back(plane);
  }
  return names;
}

UzawaOptions parse_rho(const std::string& text, const std::string& field) {
  UzawaOptions options;
  if (text == "auto") return options;
  std::string number = text;
  options.rho_rule = UzawaOptions::RhoRule::Absolute;
  if (!number.empty() && (number.back() == 'x' || number.back() == 'X')) {
    number.pop_back();
    options.rho_rule = UzawaOptions::RhoRule::FractionOfMax;
  }
  size_t used = 0;
  double value = 0;
  try {
    value = std::stod(number, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != number.size() || !std::isfinite(value) || !(value > 0))
    throw InputError(
        field,
        "= \"" + text + "\": must be \"auto\", a positive number, or a positive fraction of ρ_max such as \"0.5x\"");
  options.rho = value;
  return options;
}

Scene parse_scene(const std::string& json_text, const std::string& source) {
  const json document = detail::parse_json(json_text, source);
  // Every unknown key, at any depth, before any reader can find a key missing: a renamed
  // "material.nu" is reported as the unknown key it is, not as "material.nu is missing".
  detail::check_scene_keys(document);
  Scene scene;
  scene.source = source;
  JsonObject root(document, "");
  root.optional_string("description");  // free text for the reader of the scene file

  if (auto model = root.optional_string("model")) {
    if (*model == "plane_strain")
      scene.model = ElasticModel::PlaneStrain;
    else if (*model == "plane_stress")
      scene.model = ElasticModel::PlaneStress;
    else if (*model == "solid")
      scene.model = ElasticModel::Solid;
    else {
      detail::unknown_choice("model", *model, "model", {"plane_strain", "plane_stress", "solid"});
    }
  }
  const int dim = scene.dim();
  if (auto estimate = root.optional_boolean("estimate")) scene.estimate = *estimate;
  if (root.has("adapt")) scene.adapt = detail::read_adapt(root.object("adapt"));
  if (scene.adapt && !scene.estimate)
    throw InputError("estimate", "= false: an adaptive run (\"adapt\") needs the error estimate");
  // Tetrahedra fill a Cholesky factor far more than triangles, and nested dissection keeps it
  // down: at 1.6e5 DOFs (4-node, scenes/hertz-sphere.json refined) METIS factorised in 23 s with
  // a 2.2 GB peak against AMD's 129 s and 4.6 GB (docs/3d.md). 2D keeps AMD, measured best there.
  if (dim == 3) scene.solver.ordering = Ordering::Metis;

  if (root.has("bodies")) {  // several bodies (bodies_reader.cpp)
    detail::read_bodies(root, scene, source);
    if (root.has("steps")) detail::read_steps(root.value("steps"), scene);
    detail::check_friction(scene);
    root.finish();
    return scene;
  }
  scene.material = detail::read_material(root.object("material"));

  scene.body = detail::read_body(root.object("body"), source, dim);
  // Plane stress has a finite bulk stiffness E/(2(1 − ν)) whatever ν: nothing locks, nothing to mix.
  if (scene.body.formulation == Formulation::Mixed && scene.model == ElasticModel::Solid)
    throw InputError(
        "body.formulation",
        "= \"mixed\": only for \"model\": \"plane_strain\" (6-node triangles; tetrahedra have no mixed formulation)");
  if (scene.body.formulation == Formulation::Mixed && scene.model != PlaneModel::PlaneStrain)
    throw InputError("body.formulation",
                     "= \"mixed\": only for \"model\": \"plane_strain\" (plane stress does not lock as ν → 0.5)");
  for (const auto& [item, path] : one_or_many(root.value("load"), "load"))
    scene.loads.push_back(detail::read_load(JsonObject(*item, path), scene.body, dim));
  for (const auto& [item, path] : one_or_many(root.value("obstacle"), "obstacle"))
    scene.obstacles.push_back(detail::read_obstacle(JsonObject(*item, path), dim));
  if (root.has("contact")) scene.contact = read_contact(root.object("contact"), scene.body);
  if (scene.contact.boundary.empty()) scene.contact.boundary = default_contact_boundary(scene.body, dim);
  if (root.has("transform")) scene.transform = detail::read_transform(root.object("transform"), dim);
  if (root.has("solver")) read_solver(root.object("solver"), scene.solver);
  if (root.has("steps")) detail::read_steps(root.value("steps"), scene);
  detail::check_friction(scene);
  root.finish();
  detail::check_symmetry(scene);
  return scene;
}

Scene load_scene(const std::string& path) { return parse_scene(detail::read_input_file(path, "scene file"), path); }

}  // namespace contactqp
