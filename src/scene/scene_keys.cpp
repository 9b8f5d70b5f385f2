// Every key of the scene format (scene_keys.hpp; docs/scenes.md says what each one means).
#include "scene_keys.hpp"

#include <algorithm>
#include <set>

#include "contactqp/errors.hpp"
#include "json_reader.hpp"

namespace contactqp::detail {
namespace {

using nlohmann::json;

struct Format {
  Section material, generated_mesh, geo_mesh, body, load, obstacle, contact, transform, solver, bodies_entry, root;
  Section friction, step, adapt;
  Format();
};

Format::Format() {
  material.keys = {must("E"), must("nu")};

  generated_mesh.context = "for a generated shape";
  generated_mesh.keys = {must("size"), must("contact_size"), {"grading"}, {"order"}, {"refinements"}};
  geo_mesh.context = "for a mesh file";
  geo_mesh.keys = {{"order"}, {"size_factor"}};

  body.keys = {must("shape"), {"symmetry"}, {"formulation"}, {"thickness", nullptr, 2}};
  body.selector = "shape";
  body.variants = {
      {"half_disc", {must("radius"), must("mesh", &generated_mesh)}},
      {"rectangle", {must("width"), must("height"), must("mesh", &generated_mesh)}},
      {"hemisphere", {must("radius"), must("mesh", &generated_mesh)}},
      {"box", {must("width"), must("depth"), must("height"), must("mesh", &generated_mesh)}},
      {"mesh", {must("file"), {"mesh", &geo_mesh}}},
  };
  body.variant_dims = {{"half_disc", 2}, {"rectangle", 2}, {"hemisphere", 3}, {"box", 3}};

  // Friction (docs/friction.md): Coulomb's coefficient or Tresca's threshold, on the contact
  // boundary, an obstacle or a contact entry (a pair). "name": what the load steps call a load.
  friction.keys = {{"coefficient"}, {"threshold"}};
  // A load step: "factors" maps load names (free-form, as solver.options) to numbers.
  step.keys = {must("factors")};

  load.keys = {must("type"), {"name"}};
  load.selector = "type";
  load.variants = {
      {"displacement", {must("boundary"), must("value")}},
      {"traction", {must("boundary"), must("value")}},
      {"pressure", {must("boundary"), must("value")}},
      {"gravity", {must("density"), must("g"), {"region"}}},
      {"point", {must("value"), {"at"}, {"point"}}},  // "at" or "point"
      {"force", {must("boundary"), must("value"), {"moment"}, {"about"}}},
  };

  obstacle.keys = {must("type"), {"friction", &friction}};
  obstacle.selector = "type";
  obstacle.variants = {
      {"plane", {must("point"), must("normal")}},
      {"circle", {must("center"), must("radius")}},
      {"profile", {must("points"), must("body_side")}},
      {"sphere", {must("center"), must("radius")}},
      {"cylinder", {must("point"), must("axis"), must("radius")}},
      {"punch", {must("center"), must("axis"), must("radius")}},
  };
  obstacle.variant_dims = {{"circle", 2}, {"profile", 2}, {"sphere", 3}, {"cylinder", 3}, {"punch", 3}};

  // One body: the boundary that may touch. Several bodies: a list of pairs and boundaries.
  contact.keys = {{"boundary"}, {"max_gap"}, {"pair"}, {"rows"}, {"friction", &friction}};
  transform.keys = {must("rotate_degrees"), must("axis", nullptr, 3)};
  // "options" holds the backend's own keys, which the backend checks (--backend-option).
  // "petsc_options": PETSc's options database entries, as --petsc-options (the PETSc room reads it).
  solver.keys = {{"backend"}, {"linear_solver"}, {"tol"}, {"rho"}, {"max_iterations"}, {"options"}, {"petsc_options"}};

  // An adaptive run (docs/adaptive.md).
  adapt.keys = {must("target"), {"max_dofs"}, {"max_cycles"}};

  // A "bodies" entry: the body's own keys, then its shape as in "body".
  bodies_entry = body;
  bodies_entry.keys.insert(bodies_entry.keys.begin(),
                           {must("name"), must("material", &material), must("load", &load), {"mirror"}, {"offset"}});

  // A one-body scene requires material, body, load and obstacle; a "bodies" scene bodies and
  // contact: none is marked required, since which depends on the other keys.
  root.keys = {{"description"},         {"model"},
               {"material", &material}, {"body", &body},
               {"load", &load},         {"obstacle", &obstacle},
               {"contact", &contact},   {"transform", &transform},
               {"solver", &solver},     {"bodies", &bodies_entry},
               {"steps", &step},        {"estimate"},
               {"adapt", &adapt}};
}

const Format& format() {
  static const Format table;
  return table;
}

const Key* find_key(const std::vector<const Key*>& keys, const std::string& name) {
  for (const Key* key : keys)
    if (key->name == name) return key;
  return nullptr;
}

std::string join_path(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

// Each section once, depth first from the root.
void visit_sections(const Section& section, std::set<const Section*>& seen, std::vector<const Section*>& out) {
  if (!seen.insert(&section).second) return;
  out.push_back(&section);
  auto children = [&](const std::vector<Key>& keys) {
    for (const Key& key : keys)
      if (key.section) visit_sections(*key.section, seen, out);
  };
  children(section.keys);
  for (const auto& [value, keys] : section.variants) children(keys);
}

std::vector<const Section*> every_section() {
  std::set<const Section*> seen;
  std::vector<const Section*> out;
  visit_sections(format().root, seen, out);
  return out;
}

bool known_anywhere(const std::string& name) {
  for (const Section* section : every_section())
    for (const Key* key : section->valid_keys(json()))
      if (key->name == name) return true;
  return false;
}

// Why a key the format knows is not valid in this object: it is the other dimension's, another
// variant's, or another form of the section's (a .geo file's mesh, not a generated shape's).
std::string where_not_valid(const std::string& name, const json& object, const Section& section, int dim) {
  if (dim != 0)
    for (const Key* key : section.valid_keys(object, 0))
      if (key->name == name && key->dim != 0 && key->dim != dim)
        return dim == 2 ? " in a 2D scene (\"model\": \"solid\" is 3D)" : " in a 3D scene (\"model\": \"solid\")";
  const std::string variant = section.chosen_variant(object, dim);
  if (!variant.empty() && find_key(section.valid_keys(json()), name))
    return " for \"" + section.selector + "\": \"" + variant + "\"";
  return !section.context.empty() && known_anywhere(name) ? " " + section.context : "";
}

// Where a mis-nested key belongs: the path below this object of the first child section that
// has it ("mesh.size" for a "size" given in "body"), or "".
std::string nested_home(const std::string& name, const json& object, const Section& section, int dim) {
  for (const Key* key : section.valid_keys(object, dim)) {
    if (!key->section) continue;
    const auto child = object.find(key->name);
    const json& value = child != object.end() && child->is_object() ? *child : json();
    if (find_key(key->section->valid_keys(value, dim), name)) return key->name + "." + name;
  }
  return "";
}

void check_object(const json& object, const Section& section, const std::string& path, int dim) {
  const std::vector<const Key*> valid = section.valid_keys(object, dim);
  for (const auto& item : object.items()) {
    if (find_key(valid, item.key())) continue;
    // A key one level too high ("size" in "body" for "body.mesh.size"); else a misspelling of
    // a valid key; else perhaps a renamed required one ("poisson" for "nu").
    std::string hint = nested_home(item.key(), object, section, dim);
    std::vector<std::string> names;
    for (const Key* key : valid) names.push_back(key->name);
    if (hint.empty()) hint = nearest(item.key(), names);
    for (const Key* key : valid)
      if (hint.empty() && key->required && !object.contains(key->name)) hint = key->name;
    throw InputError(join_path(path, item.key()),
                     "is not a valid key" + where_not_valid(item.key(), object, section, dim) +
                         (hint.empty() ? std::string() : "; did you mean \"" + join_path(path, hint) + "\"?"));
  }
  for (const auto& item : object.items()) {
    const Key* key = find_key(valid, item.key());
    const json& value = item.value();
    const std::string child = join_path(path, item.key());
    if (!key->section) continue;
    if (value.is_object()) check_object(value, *key->section, child, dim);
    if (value.is_array())
      for (size_t i = 0; i < value.size(); ++i)
        if (value[i].is_object()) check_object(value[i], *key->section, child + "[" + std::to_string(i) + "]", dim);
  }
}

}  // namespace

Key must(std::string name, const Section* section, int dim) { return Key{std::move(name), section, dim, true}; }

std::string Section::chosen_variant(const json& object, int dim) const {
  if (selector.empty() || !object.is_object()) return "";
  const auto selected = object.find(selector);
  if (selected == object.end() || !selected->is_string()) return "";
  const std::string value = selected->get<std::string>();
  if (!variants.count(value)) return "";
  const auto only = variant_dims.find(value);
  if (dim != 0 && only != variant_dims.end() && only->second != dim) return "";
  return value;
}

std::vector<const Key*> Section::valid_keys(const json& object, int dim) const {
  std::vector<const Key*> out;
  auto add = [&](const std::vector<Key>& list) {
    for (const Key& key : list)
      if (dim == 0 || key.dim == 0 || key.dim == dim) out.push_back(&key);
  };
  add(keys);
  if (selector.empty()) return out;
  const std::string chosen = chosen_variant(object, dim);
  if (!chosen.empty()) {
    add(variants.at(chosen));
  } else {
    for (const auto& [value, list] : variants) add(list);
  }
  return out;
}

const Section& scene_section() { return format().root; }
const Section& body_section() { return format().body; }

const Section* section_at(const std::string& path) {
  const Section* section = &format().root;
  size_t start = 0;
  while (section && start < path.size()) {
    size_t end = path.find('.', start);
    if (end == std::string::npos) end = path.size();
    std::string name = path.substr(start, end - start);
    name = name.substr(0, name.find('['));  // "load[2]" is an entry of "load"
    const Key* key = find_key(section->valid_keys(json()), name);
    section = key ? key->section : nullptr;
    start = end + 1;
  }
  return section;
}

void check_scene_keys(const json& document) {
  if (!document.is_object()) return;  // the root reader says what it must be
  int dim = 2;                        // "model" defaults to plane strain
  const auto model = document.find("model");
  if (model != document.end())
    dim = !model->is_string()                                      ? 0
          : *model == "solid"                                      ? 3
          : (*model == "plane_strain" || *model == "plane_stress") ? 2
                                                                   : 0;  // 0: the reader names a bad model
  check_object(document, format().root, "", dim);
}

std::vector<std::string> scene_words() {
  std::set<std::string> words;
  for (const Section* section : every_section()) {
    for (const Key* key : section->valid_keys(json())) words.insert(key->name);
    for (const auto& [value, keys] : section->variants) words.insert(value);
  }
  return {words.begin(), words.end()};
}

}  // namespace contactqp::detail
