// One entry of the `load` section: prescribed displacement, traction, pressure, gravity, or
// a point force.
#include <algorithm>

#include "contactqp/errors.hpp"
#include "readers.hpp"

namespace contactqp::detail {
namespace {

const std::vector<std::string> kLoadTypes = {"displacement", "traction", "pressure", "gravity", "point"};

void read_displacement(JsonObject& load, LoadSpec& spec, int dim) {
  const nlohmann::json& value = load.value("value");
  const std::string path = load.path_of("value");
  if (!value.is_array() || static_cast<int>(value.size()) != dim)
    throw InputError(path, "= " + describe(value) +
                               (dim == 2 ? ": must be [ux, uy], a component null when free"
                                         : ": must be [ux, uy, uz], a component null when free"));
  bool any = false;
  for (int c = 0; c < dim; ++c)
    if (!value[c].is_null()) {
      spec.value[c] = as_number(value[c], path + "[" + std::to_string(c) + "]");
      any = true;
    }
  if (!any)
    throw InputError(
        path, std::string(dim == 2 ? "= [null, null]" : "= [null, null, null]") + ": prescribe at least one component");
}

void read_point(JsonObject& load, LoadSpec& spec, const BodySpec& body, int dim) {
  spec.vector = read_vector(load.value("value"), load.path_of("value"), dim);
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
}

}  // namespace

LoadSpec read_load(JsonObject load, const BodySpec& body, int dim) {
  LoadSpec spec;
  spec.path = load.path();
  spec.type = load.string("type");
  if (std::find(kLoadTypes.begin(), kLoadTypes.end(), spec.type) == kLoadTypes.end())
    unknown_choice(load.path_of("type"), spec.type, "load type", kLoadTypes);
  if (spec.type == "displacement" || spec.type == "traction" || spec.type == "pressure") {
    spec.boundary = load.string("boundary");
    require_boundary(spec.boundary, body, load.path_of("boundary"));
  }
  if (spec.type == "displacement") {
    read_displacement(load, spec, dim);
  } else if (spec.type == "traction") {
    spec.vector = read_vector(load.value("value"), load.path_of("value"), dim);
  } else if (spec.type == "pressure") {
    spec.pressure = load.number("value");
  } else if (spec.type == "gravity") {
    spec.density = load.number("density");
    require(spec.density > 0, load.path_of("density"), spec.density, "must be positive");
    spec.vector = read_vector(load.value("g"), load.path_of("g"), dim);
    if (auto region = load.optional_string("region")) {
      spec.region = *region;
      if (body.shape != "mesh")
        throw InputError(load.path_of("region"), "= \"" + spec.region + "\": a " + body.shape +
                                                     " has no named regions; leave \"region\" out for the whole body");
    }
  } else {
    read_point(load, spec, body, dim);
  }
  load.finish();
  return spec;
}

}  // namespace contactqp::detail
