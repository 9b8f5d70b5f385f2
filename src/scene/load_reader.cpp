// One entry of the `load` section: prescribed displacement, traction, pressure, gravity, a
// point force, or a force on a rigid surface.
#include <algorithm>
#include <type_traits>
#include <utility>
#include <variant>

#include "contactqp/errors.hpp"
#include "readers.hpp"

namespace contactqp::detail {
namespace {

const std::vector<std::string> kLoadTypes = {"displacement", "traction", "pressure", "gravity", "point", "force"};

// "value": dim components, each a number or null (free); at least one a number. A displacement
// prescribes them, a force on a rigid surface ties them.
template <class Load>
Load read_components(JsonObject& load, std::string boundary, int dim) {
  Load spec;
  spec.boundary = std::move(boundary);
  const nlohmann::json& value = load.value("value");
  const std::string path = load.path_of("value");
  const char* letter = std::is_same_v<Load, DisplacementLoad> ? "u" : "F";
  if (!value.is_array() || static_cast<int>(value.size()) != dim)
    throw InputError(path, "= " + describe(value) + ": must be [" + letter + "x, " + letter + "y" +
                               (dim == 2 ? "" : std::string(", ") + letter + "z") + "], a component null when free");
  bool any = false;
  for (int c = 0; c < dim; ++c)
    if (!value[c].is_null()) {
      spec.value[c] = as_number(value[c], path + "[" + std::to_string(c) + "]");
      any = true;
    }
  if (!any)
    throw InputError(path, std::string(dim == 2 ? "= [null, null]" : "= [null, null, null]") +
                               (std::is_same_v<Load, DisplacementLoad>
                                    ? ": prescribe at least one component"
                                    : ": give at least one component of the force (null leaves a component free)"));
  return spec;
}

// A force load's "moment" (2D: a number, about z; 3D: [Mx, My, Mz], null where the surface
// does not turn) and "about", the point it is taken about.
void read_moment(JsonObject& load, int dim, RigidForceLoad& spec) {
  if (load.has("moment")) {
    const nlohmann::json& value = load.value("moment");
    const std::string path = load.path_of("moment");
    if (dim == 2) {
      if (!value.is_number())
        throw InputError(path, "= " + describe(value) + ": must be a number, the moment about z (0: free to turn)");
      spec.moment[2] = as_number(value, path);
    } else {
      if (!value.is_array() || value.size() != 3)
        throw InputError(
            path, "= " + describe(value) + ": must be [Mx, My, Mz], a component null where the surface does not turn");
      for (int a = 0; a < 3; ++a)
        if (!value[a].is_null()) spec.moment[a] = as_number(value[a], path + "[" + std::to_string(a) + "]");
      if (!spec.turns())
        throw InputError(path, "= [null, null, null]: give at least one component (0: free to turn about that axis)");
    }
  }
  if (load.has("about")) {
    if (!spec.turns())
      throw InputError(load.path_of("about"), "is the point a moment is taken about: give \"moment\" too");
    spec.about = read_vector(load.value("about"), load.path_of("about"), dim);
  }
}

GravityLoad read_gravity(JsonObject& load, const BodySpec& body, int dim) {
  GravityLoad spec;
  spec.density = load.number("density");
  require(spec.density > 0, load.path_of("density"), spec.density, "must be positive");
  spec.g = read_vector(load.value("g"), load.path_of("g"), dim);
  if (auto region = load.optional_string("region")) {
    spec.region = *region;
    if (body.shape != "mesh")
      throw InputError(load.path_of("region"), "= \"" + spec.region + "\": a " + body.shape +
                                                   " has no named regions; leave \"region\" out for the whole body");
  }
  return spec;
}

PointLoad read_point(JsonObject& load, const BodySpec& body, int dim) {
  PointLoad spec;
  spec.force = read_vector(load.value("value"), load.path_of("value"), dim);
  const bool has_at = load.has("at"), has_point = load.has("point");
  if (has_at == has_point)
    throw InputError(load.path(), std::string(has_at ? "has both" : "needs one of") +
                                      " \"at\": " + (dim == 2 ? "[x, y]" : "[x, y, z]") +
                                      " (the nearest node takes the force) and \"point\": a physical point's name");
  if (has_at) spec.at = read_vector(load.value("at"), load.path_of("at"), dim);
  if (has_point) {
    spec.point = load.string("point");
    if (body.shape != "mesh")
      throw InputError(load.path_of("point"),
                       "= \"" + spec.point + "\": a " + body.shape +
                           " has no named points; give \"at\": " + (dim == 2 ? "[x, y]" : "[x, y, z]") + " instead");
  }
  return spec;
}

}  // namespace

LoadSpec read_load(JsonObject load, const BodySpec& body, int dim) {
  LoadSpec spec;
  spec.path = load.path();
  if (auto name = load.optional_string("name")) {
    spec.name = *name;
    if (spec.name.empty()) throw InputError(load.path_of("name"), "= \"\": must be a non-empty name");
  }
  const std::string type = load.string("type");
  if (std::find(kLoadTypes.begin(), kLoadTypes.end(), type) == kLoadTypes.end())
    unknown_choice(load.path_of("type"), type, "load type", kLoadTypes);
  std::string boundary;
  if (type == "displacement" || type == "traction" || type == "pressure" || type == "force") {
    boundary = load.string("boundary");
    require_boundary(boundary, body, load.path_of("boundary"));
  }
  if (type == "displacement") {
    spec.kind = read_components<DisplacementLoad>(load, std::move(boundary), dim);
  } else if (type == "force") {
    RigidForceLoad force = read_components<RigidForceLoad>(load, std::move(boundary), dim);
    read_moment(load, dim, force);
    spec.kind = std::move(force);
  } else if (type == "traction") {
    spec.kind = TractionLoad{std::move(boundary), read_vector(load.value("value"), load.path_of("value"), dim)};
  } else if (type == "pressure") {
    spec.kind = PressureLoad{std::move(boundary), load.number("value")};
  } else if (type == "gravity") {
    spec.kind = read_gravity(load, body, dim);
  } else {
    spec.kind = read_point(load, body, dim);
  }
  load.finish();
  return spec;
}

}  // namespace contactqp::detail

namespace contactqp {

std::string LoadSpec::type() const {
  if (is<DisplacementLoad>()) return "displacement";
  if (is<TractionLoad>()) return "traction";
  if (is<PressureLoad>()) return "pressure";
  if (is<GravityLoad>()) return "gravity";
  if (is<RigidForceLoad>()) return "force";
  return "point";
}

namespace {

// The boundary of a displacement, traction, pressure or rigid force; nullptr for the other kinds.
template <class Kinds>
auto boundary_of(Kinds& kind) {
  using Pointer = std::conditional_t<std::is_const_v<Kinds>, const std::string*, std::string*>;
  return std::visit(
      [](auto& load) -> Pointer {
        using Kind = std::decay_t<decltype(load)>;
        if constexpr (std::is_same_v<Kind, GravityLoad> || std::is_same_v<Kind, PointLoad>)
          return nullptr;
        else
          return &load.boundary;
      },
      kind);
}

}  // namespace

const std::string* LoadSpec::boundary() const { return boundary_of(kind); }
std::string* LoadSpec::boundary() { return boundary_of(kind); }

}  // namespace contactqp
