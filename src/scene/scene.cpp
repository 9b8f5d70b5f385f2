// Reading and validating scene files. Every rule a value must satisfy is checked here, once,
// before any mesh is built, so that bad input fails fast with the field's name.
#include "contactqp/scene.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "contactqp/errors.hpp"
#include "json_reader.hpp"

namespace contactqp {
namespace {

using detail::describe;
using detail::JsonObject;
using nlohmann::json;

Eigen::Vector2d read_vector(const json& value, const std::string& path) {
  if (!value.is_array() || value.size() != 2)
    throw InputError(path, "= " + describe(value) + ": must be an array of two numbers [x, y]");
  return {detail::as_number(value[0], path + "[0]"), detail::as_number(value[1], path + "[1]")};
}

std::string join(const std::vector<std::string>& words) {
  std::string text;
  for (const auto& word : words) text += (text.empty() ? "" : ", ") + word;
  return text;
}

void require_boundary(const std::string& name, const BodySpec& body, const std::string& path) {
  const std::vector<std::string> names = boundary_names(body);
  for (const auto& known : names)
    if (name == known) return;
  const std::string hint = detail::nearest(name, names);
  throw InputError(path, "= \"" + name + "\": not a boundary of a " + body.shape +
                             (body.symmetry ? " with symmetry" : "") + "; valid: " + join(names) +
                             (hint.empty() ? "" : "; did you mean \"" + hint + "\"?"));
}

MeshSpec read_mesh(JsonObject mesh) {
  MeshSpec spec;
  spec.size = mesh.number("size");
  require(spec.size > 0, mesh.path_of("size"), spec.size, "must be positive");
  spec.contact_size = mesh.number("contact_size");
  require(spec.contact_size > 0, mesh.path_of("contact_size"), spec.contact_size, "must be positive");
  require(spec.contact_size <= spec.size, mesh.path_of("contact_size"), spec.contact_size,
          "must not exceed body.mesh.size = " + detail::format_value(spec.size));
  if (auto grading = mesh.optional_number("grading")) {
    spec.grading = *grading;
    require(spec.grading > 0 && spec.grading <= 1, mesh.path_of("grading"), spec.grading, "must lie in (0, 1]");
  }
  if (auto order = mesh.optional_integer("order")) {
    spec.order = *order;
    require(spec.order == 1 || spec.order == 2, mesh.path_of("order"), spec.order, "must be 1 or 2");
  }
  mesh.finish();
  return spec;
}

BodySpec read_body(JsonObject body) {
  BodySpec spec;
  spec.shape = body.string("shape");
  if (spec.shape != "half_disc") {
    const std::string hint = detail::nearest(spec.shape, {"half_disc"});
    throw InputError(body.path_of("shape"), "= \"" + spec.shape + "\": unknown shape; valid: half_disc" +
                                                (hint.empty() ? "" : "; did you mean \"" + hint + "\"?"));
  }
  spec.radius = body.number("radius");
  require(spec.radius > 0, body.path_of("radius"), spec.radius, "must be positive");
  spec.symmetry = body.optional_boolean("symmetry").value_or(false);
  if (auto thickness = body.optional_number("thickness")) {
    spec.thickness = *thickness;
    require(spec.thickness > 0, body.path_of("thickness"), spec.thickness, "must be positive");
  }
  spec.mesh = read_mesh(body.object("mesh"));
  require(spec.mesh.contact_size <= spec.radius, body.path_of("mesh.contact_size"), spec.mesh.contact_size,
          "must not exceed body.radius = " + detail::format_value(spec.radius));
  body.finish();
  return spec;
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

LoadSpec read_load(JsonObject load, const BodySpec& body) {
  LoadSpec spec;
  spec.type = load.string("type");
  if (spec.type != "displacement") {
    const std::string hint = detail::nearest(spec.type, {"displacement"});
    throw InputError(load.path_of("type"), "= \"" + spec.type + "\": unknown load type; valid: displacement" +
                                               (hint.empty() ? "" : "; did you mean \"" + hint + "\"?"));
  }
  spec.boundary = load.string("boundary");
  require_boundary(spec.boundary, body, load.path_of("boundary"));
  const json& value = load.value("value");
  const std::string path = load.path_of("value");
  if (!value.is_array() || value.size() != 2)
    throw InputError(path, "= " + describe(value) + ": must be [ux, uy], a component null when free");
  for (int c = 0; c < 2; ++c)
    if (!value[c].is_null()) spec.value[c] = detail::as_number(value[c], path + "[" + std::to_string(c) + "]");
  if (!spec.value[0] && !spec.value[1])
    throw InputError(path, "= [null, null]: prescribe at least one component");
  load.finish();
  return spec;
}

ObstacleSpec read_obstacle(JsonObject obstacle) {
  ObstacleSpec spec;
  spec.type = obstacle.string("type");
  if (spec.type != "plane") {
    const std::string hint = detail::nearest(spec.type, {"plane"});
    throw InputError(obstacle.path_of("type"), "= \"" + spec.type + "\": unknown obstacle type; valid: plane" +
                                                   (hint.empty() ? "" : "; did you mean \"" + hint + "\"?"));
  }
  spec.point = read_vector(obstacle.value("point"), obstacle.path_of("point"));
  spec.normal = read_vector(obstacle.value("normal"), obstacle.path_of("normal"));
  const double length = spec.normal.norm();
  if (!(length > 0))
    throw InputError(obstacle.path_of("normal"), "= [0, 0]: must be a non-zero vector");
  spec.normal /= length;
  obstacle.finish();
  return spec;
}

ContactSpec read_contact(JsonObject contact, const BodySpec& body) {
  ContactSpec spec;
  if (auto boundary = contact.optional_string("boundary")) {
    spec.boundary = *boundary;
    require_boundary(spec.boundary, body, contact.path_of("boundary"));
  }
  spec.max_gap = contact.optional_number("max_gap");
  if (spec.max_gap) require(*spec.max_gap >= 0, contact.path_of("max_gap"), *spec.max_gap, "must be ≥ 0");
  contact.finish();
  return spec;
}

void read_solver(JsonObject solver, SolveOptions& options) {
  if (auto backend = solver.optional_string("backend"))
    options.backend = parse_backend(*backend, solver.path_of("backend"));
  if (auto tol = solver.optional_number("tol")) {
    options.tol = *tol;
    require(*tol > 0 && *tol < 1, solver.path_of("tol"), *tol, "must lie in (0, 1)");
  }
  if (solver.has("rho")) {
    const json& rho = solver.value("rho");
    if (rho.is_number()) {
      options.uzawa.rho_rule = UzawaOptions::RhoRule::Absolute;
      options.uzawa.rho = detail::as_number(rho, solver.path_of("rho"));
      require(options.uzawa.rho > 0, solver.path_of("rho"), options.uzawa.rho, "must be positive");
    } else if (rho.is_string()) {
      options.uzawa = parse_rho(rho.get<std::string>(), solver.path_of("rho"));
    } else {
      throw InputError(solver.path_of("rho"), "= " + describe(rho) + ": must be \"auto\", a number, or a fraction of ρ_max such as \"0.5x\"");
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
    if (!entries.is_object())
      throw InputError(path, "= " + describe(entries) + ": must be an object {\"key\": value}");
    for (const auto& [key, value] : entries.items()) {
      if (value.is_string()) options.backend_options[key] = value.get<std::string>();
      else if (value.is_number()) options.backend_options[key] = value.dump();
      else throw InputError(path + "." + key, "= " + describe(value) + ": must be a string or a number");
    }
  }
  solver.finish();
}

void check_symmetry(const Scene& scene) {
  if (!scene.body.symmetry) return;
  // Modelling x ≥ 0 alone is right only when the rest of the scene is mirror-symmetric.
  for (size_t i = 0; i < scene.obstacles.size(); ++i) {
    const ObstacleSpec& o = scene.obstacles[i];
    if (std::abs(o.normal.x()) > 1e-12 || std::abs(o.point.x()) > 0)
      throw InputError("body.symmetry", "= true: obstacle " + std::to_string(i) +
                                            " is not symmetric about x = 0 (its point must have x = 0 and its normal no x component); set \"symmetry\": false");
  }
  for (const LoadSpec& load : scene.loads)
    if (load.value[0] && *load.value[0] != 0.0)
      throw InputError("body.symmetry", "= true: the load on \"" + load.boundary + "\" has ux = " +
                                            detail::format_value(*load.value[0]) + " ≠ 0, which breaks the symmetry; set \"symmetry\": false");
}

}  // namespace

std::string to_string(PlaneModel model) {
  return model == PlaneModel::PlaneStrain ? "plane_strain" : "plane_stress";
}

std::vector<std::string> boundary_names(const BodySpec& body) {
  std::vector<std::string> names = {"arc", "top"};
  if (body.symmetry) names.push_back("symmetry");
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
    throw InputError(field, "= \"" + text + "\": must be \"auto\", a positive number, or a positive fraction of ρ_max such as \"0.5x\"");
  options.rho = value;
  return options;
}

Scene parse_scene(const std::string& json_text, const std::string& source) {
  json document;
  try {
    document = json::parse(json_text);
  } catch (const json::parse_error& error) {
    std::string what = error.what();
    const auto bracket = what.find("] ");
    if (bracket != std::string::npos) what = what.substr(bracket + 2);
    throw InputError(source, "is not valid JSON: " + what);
  }
  Scene scene;
  scene.source = source;
  JsonObject root(document, "");
  root.optional_string("description");  // free text for the reader of the scene file

  if (auto model = root.optional_string("model")) {
    if (*model == "plane_strain") scene.model = PlaneModel::PlaneStrain;
    else if (*model == "plane_stress") scene.model = PlaneModel::PlaneStress;
    else {
      const std::string hint = detail::nearest(*model, {"plane_strain", "plane_stress"});
      throw InputError("model", "= \"" + *model + "\": valid: plane_strain, plane_stress" +
                                    (hint.empty() ? "" : "; did you mean \"" + hint + "\"?"));
    }
  }

  JsonObject material = root.object("material");
  scene.material.E = material.number("E");
  require(scene.material.E > 0, "material.E", scene.material.E, "must be positive");
  scene.material.nu = material.number("nu");
  require(scene.material.nu > -1 && scene.material.nu < 0.5, "material.nu", scene.material.nu, "must lie in (-1, 0.5)");
  material.finish();

  scene.body = read_body(root.object("body"));
  for (const auto& [item, path] : one_or_many(root.value("load"), "load"))
    scene.loads.push_back(read_load(JsonObject(*item, path), scene.body));
  for (const auto& [item, path] : one_or_many(root.value("obstacle"), "obstacle"))
    scene.obstacles.push_back(read_obstacle(JsonObject(*item, path)));
  if (root.has("contact")) scene.contact = read_contact(root.object("contact"), scene.body);
  if (scene.contact.boundary.empty()) scene.contact.boundary = "arc";
  if (root.has("solver")) read_solver(root.object("solver"), scene.solver);
  root.finish();
  check_symmetry(scene);
  return scene;
}

Scene load_scene(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw InputError(path, "is a directory, not a scene file");
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path, "cannot be read: no such file, or no permission");
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) throw InputError(path, "cannot be read");
  return parse_scene(text.str(), path);
}

}  // namespace contactqp
