// A scene with several elastic bodies: the "bodies" list, the contact pairs between their
// boundaries and the boundaries that may touch the rigid obstacles (docs/bodies.md).
#include <algorithm>
#include <cmath>
#include <set>

#include "contactqp/errors.hpp"
#include "readers.hpp"

namespace contactqp {

Eigen::Vector3d BodyPlacement::to_global(const Eigen::Vector3d& local, int dim) const {
  Eigen::Vector3d x = local;
  if (mirror) x[dim - 1] = -x[dim - 1];
  return x + offset;
}

Eigen::Vector3d BodyPlacement::to_local(const Eigen::Vector3d& global, int dim) const {
  Eigen::Vector3d x = global - offset;
  if (mirror) x[dim - 1] = -x[dim - 1];
  return x;
}

Eigen::Vector3d BodyPlacement::direction_to_local(const Eigen::Vector3d& direction, int dim) const {
  Eigen::Vector3d d = direction;
  if (mirror) d[dim - 1] = -d[dim - 1];
  return d;
}

namespace detail {
namespace {

using nlohmann::json;

// The keys of a bodies entry that are the body's own, not its shape's.
const std::vector<std::string> kBodyEntryKeys = {"name", "material", "load", "mirror", "offset"};

SceneBody read_scene_body(const json& entry, const std::string& path, const std::string& source, int dim) {
  if (!entry.is_object()) throw InputError(path, "= " + describe(entry) + ": must be an object");
  SceneBody body;
  body.path = path;
  JsonObject own(entry, path);
  body.name = own.string("name");
  if (body.name.empty() || body.name.find('.') != std::string::npos)
    throw InputError(own.path_of("name"), "= \"" + body.name + "\": must be a non-empty name without '.'");
  body.material = read_material(own.object("material"));
  if (auto mirror = own.optional_boolean("mirror")) body.placement.mirror = *mirror;
  if (own.has("offset")) body.placement.offset = read_vector(own.value("offset"), own.path_of("offset"), dim);
  // The rest of the entry is the shape, read as a one-body scene's "body" section.
  json shape = entry;
  for (const std::string& key : kBodyEntryKeys) shape.erase(key);
  body.body = read_body(JsonObject(shape, path), source, dim);
  if (body.body.formulation == Formulation::Mixed && dim == 3)
    throw InputError(path + ".formulation", "= \"mixed\": only for \"model\": \"plane_strain\"");
  if (body.body.symmetry)
    for (int c = 0; c < dim - 1; ++c)
      if (symmetric_about(body.body, c, dim) && body.placement.offset[c] != 0.0)
        throw InputError(own.path_of("offset"),
                         "= " + format_point(body.placement.offset, dim) + ": a body with symmetry keeps its cut on " +
                             (c == 0 ? "x = 0" : "y = 0") + " (offset only along " + (dim == 2 ? "y" : "z") + ")");
  // A body without a load (a ball between two plates) is held by its contacts alone: the
  // rigid-motion check refuses it, naming the motion, when no candidate row can stop one.
  if (own.has("load"))
    for (const auto& [item, load_path] : one_or_many(own.value("load"), own.path_of("load")))
      body.loads.push_back(read_load(JsonObject(*item, load_path), body.body, dim));
  return body;
}

// "roller.surface" → (body index, "surface"), or InputError naming the field.
std::pair<int, std::string> body_boundary(const json& value, const std::string& path, const Scene& scene) {
  if (!value.is_string()) throw InputError(path, "= " + describe(value) + ": must be a string \"body.boundary\"");
  const std::string text = value.get<std::string>();
  const auto dot = text.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == text.size())
    throw InputError(path, "= \"" + text + "\": must name a body and one of its boundaries, \"body.boundary\"");
  const std::string name = text.substr(0, dot), boundary = text.substr(dot + 1);
  std::vector<std::string> names;
  for (const SceneBody& body : scene.bodies) names.push_back(body.name);
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) {
    const std::string hint = nearest(name, names);
    throw InputError(path, "= \"" + text + "\": no body named \"" + name + "\"; bodies: " + join(names) +
                               (hint.empty() ? "" : "; did you mean \"" + hint + "." + boundary + "\"?"));
  }
  const int index = static_cast<int>(it - names.begin());
  try {
    require_boundary(boundary, scene.bodies[index].body, path);
  } catch (const InputError& error) {  // name the whole "body.boundary" as written
    const std::string what = error.what(), tail = what.substr(what.find(": ") + 2);
    throw InputError(path, "= \"" + text + "\": " + tail);
  }
  return {index, boundary};
}

std::optional<double> read_max_gap(JsonObject& entry) {
  auto max_gap = entry.optional_number("max_gap");
  if (max_gap) require(*max_gap >= 0, entry.path_of("max_gap"), *max_gap, "must be ≥ 0");
  return max_gap;
}

void read_contact_entry(JsonObject entry, Scene& scene) {
  if (entry.has("pair")) {
    ContactPair pair;
    pair.path = entry.path();
    const json& sides = entry.value("pair");
    if (!sides.is_array() || sides.size() != 2)
      throw InputError(entry.path_of("pair"),
                       "= " + describe(sides) + ": must be two boundaries [\"body.boundary\", \"body.boundary\"]");
    for (int k = 0; k < 2; ++k) {
      auto [body, boundary] = body_boundary(sides[k], entry.path_of("pair") + "[" + std::to_string(k) + "]", scene);
      pair.body[k] = body;
      pair.boundary[k] = boundary;
    }
    if (pair.body[0] == pair.body[1])
      throw InputError(entry.path_of("pair"), "= " + describe(sides) + ": both sides are body \"" +
                                                  scene.bodies[pair.body[0]].name +
                                                  "\"; a pair couples two different bodies");
    pair.max_gap = read_max_gap(entry);
    if (auto rows = entry.optional_string("rows")) {
      if (*rows == "mortar")
        pair.rows = PairRows::Mortar;
      else if (*rows != "node_to_face")
        unknown_choice(entry.path_of("rows"), *rows, "rows", {"node_to_face", "mortar"});
    }
    if (entry.has("friction")) pair.friction = read_friction(entry.object("friction"));
    // Mortar rows and friction: the tangential rows of a node on a symmetry plane then reach
    // its neighbours off the plane, and the rows of a half model become dependent there
    // (docs/bodies.md, "Mortar rows"). Until that is solved, friction keeps node-to-face rows.
    if (pair.rows == PairRows::Mortar && pair.friction &&
        (pair.friction->coefficient > 0 || pair.friction->threshold > 0))
      throw InputError(entry.path_of("rows"),
                       "= \"mortar\": not with friction yet; a pair with friction has node-to-face rows "
                       "(\"rows\": \"node_to_face\", the default)");
    entry.finish();
    scene.pairs.push_back(pair);
    return;
  }
  ObstacleContactSpec spec;
  spec.path = entry.path();
  auto [body, boundary] = body_boundary(entry.value("boundary"), entry.path_of("boundary"), scene);
  spec.body = body;
  spec.boundary = boundary;
  spec.max_gap = read_max_gap(entry);
  if (entry.has("friction")) spec.friction = read_friction(entry.object("friction"));
  entry.finish({"pair"});
  scene.obstacle_contacts.push_back(spec);
}

}  // namespace

void read_bodies(JsonObject& root, Scene& scene, const std::string& source) {
  const int dim = scene.dim();
  const json& list = root.value("bodies");
  if (!list.is_array() || list.empty())
    throw InputError("bodies", "= " + describe(list) + ": must be a non-empty array of bodies");
  std::set<std::string> names;
  for (size_t i = 0; i < list.size(); ++i) {
    SceneBody body = read_scene_body(list[i], "bodies[" + std::to_string(i) + "]", source, dim);
    if (!names.insert(body.name).second)
      throw InputError(body.path + ".name", "= \"" + body.name + "\": another body has this name");
    scene.bodies.push_back(std::move(body));
  }
  const SceneBody& first = scene.bodies.front();
  for (const SceneBody& body : scene.bodies) {
    // One symmetry plane and one thickness for the whole model: the halves must match.
    if (symmetry_boundaries(body.body, 3) != symmetry_boundaries(first.body, 3))
      throw InputError(body.path + ".symmetry", "= " + symmetry_name(body.body) +
                                                    ": every body of a scene is modelled with the same symmetry (" +
                                                    first.path + " has " + symmetry_name(first.body) + ")");
    if (body.body.thickness != first.body.thickness)
      throw InputError(body.path + ".thickness", "= " + format_value(body.body.thickness) +
                                                     ": every body of a scene has the same thickness (" +
                                                     format_value(first.body.thickness) + ")");
  }
  if (root.has("obstacle"))
    for (const auto& [item, path] : one_or_many(root.value("obstacle"), "obstacle"))
      scene.obstacles.push_back(read_obstacle(JsonObject(*item, path), dim));
  if (!root.has("contact"))
    throw InputError("contact",
                     "is missing: name the pairs that may touch, [{\"pair\": [\"a.boundary\", "
                     "\"b.boundary\"]}]");
  for (const auto& [item, path] : one_or_many(root.value("contact"), "contact")) {
    if (!item->is_object()) throw InputError(path, "= " + describe(*item) + ": must be an object");
    read_contact_entry(JsonObject(*item, path), scene);
  }
  if (!scene.obstacles.empty() && scene.obstacle_contacts.empty())
    throw InputError("contact",
                     "names no boundary that may touch the obstacles; add {\"boundary\": \"body.boundary\"}");
  if (scene.obstacles.empty() && !scene.obstacle_contacts.empty())
    throw InputError(scene.obstacle_contacts.front().path,
                     "names a boundary for the obstacles, but the scene has none");
  if (root.has("transform"))
    throw InputError("transform", "is not supported with \"bodies\": place each body by its \"offset\" and \"mirror\"");
  if (root.has("solver")) read_solver(root.object("solver"), scene.solver);
  // What reads one body's fields sees the first body's.
  scene.material = first.material;
  scene.body = first.body;
  scene.contact.boundary = scene.obstacle_contacts.empty() ? "" : scene.obstacle_contacts.front().boundary;
  // Each body's loads and the obstacles are mirror-symmetric like a one-body scene's.
  for (const SceneBody& body : scene.bodies) {
    Scene one = scene;
    one.bodies.clear();
    one.body = body.body;
    one.loads = body.loads;
    check_symmetry(one);
  }
}

}  // namespace detail
}  // namespace contactqp
