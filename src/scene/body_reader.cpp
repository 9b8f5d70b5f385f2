// The `body` section: a generated shape (half disc, rectangle) with its mesh request, or a
// Gmsh file.
#include <algorithm>
#include <filesystem>

#include "contactqp/errors.hpp"
#include "readers.hpp"

namespace contactqp::detail {
namespace {

const std::vector<std::string> kShapes2d = {"half_disc", "rectangle", "mesh"};
const std::vector<std::string> kShapes3d = {"hemisphere", "box", "mesh"};
const std::vector<std::string> kFormulations = {"displacement", "mixed"};

// The element order the mixed formulation needs: 6-node triangles (P2–P0 is inf-sup stable;
// with 3-node triangles the divergence is already constant per element and nothing changes).
constexpr int kMixedOrder = 2;

void require_mixed_order(int order, const std::string& path) {
  require(order == kMixedOrder, path, order,
          "must be 2 with \"formulation\": \"mixed\" (6-node triangles; on 3-node ones the mixed formulation "
          "is the displacement one and locks)");
}

MeshSpec read_generated_mesh(JsonObject mesh, Formulation formulation) {
  MeshSpec spec;
  if (formulation == Formulation::Mixed) spec.order = kMixedOrder;
  spec.size = mesh.number("size");
  require(spec.size > 0, mesh.path_of("size"), spec.size, "must be positive");
  spec.contact_size = mesh.number("contact_size");
  require(spec.contact_size > 0, mesh.path_of("contact_size"), spec.contact_size, "must be positive");
  require(spec.contact_size <= spec.size, mesh.path_of("contact_size"), spec.contact_size,
          "must not exceed body.mesh.size = " + format_value(spec.size));
  if (auto grading = mesh.optional_number("grading")) {
    spec.grading = *grading;
    require(spec.grading > 0 && spec.grading <= 1, mesh.path_of("grading"), spec.grading, "must lie in (0, 1]");
  }
  if (auto order = mesh.optional_integer("order")) {
    spec.order = *order;
    require(spec.order == 1 || spec.order == 2, mesh.path_of("order"), spec.order, "must be 1 or 2");
    if (formulation == Formulation::Mixed) require_mixed_order(spec.order, mesh.path_of("order"));
  }
  if (auto refinements = mesh.optional_integer("refinements")) {
    spec.refinements = *refinements;
    require(spec.refinements >= 0 && spec.refinements <= 4, mesh.path_of("refinements"), spec.refinements,
            "must be an integer from 0 to 4");
  }
  mesh.finish();
  return spec;
}

// A .geo file is meshed by Gmsh when the scene is solved: the scene may ask for quadratic
// elements and scale every size; a .msh file is the mesh as it is.
MeshSpec read_geo_options(JsonObject mesh, Formulation formulation) {
  MeshSpec spec;
  spec.order =
      formulation == Formulation::Mixed ? kMixedOrder : 0;  // 0: the .geo file's Mesh.ElementOrder, 1 by default
  if (auto order = mesh.optional_integer("order")) {
    spec.order = *order;
    require(spec.order == 1 || spec.order == 2, mesh.path_of("order"), spec.order, "must be 1 or 2");
    if (formulation == Formulation::Mixed) require_mixed_order(spec.order, mesh.path_of("order"));
  }
  if (auto factor = mesh.optional_number("size_factor")) {
    spec.size_factor = *factor;
    require(spec.size_factor > 0, mesh.path_of("size_factor"), spec.size_factor, "must be positive");
  }
  mesh.finish();
  return spec;
}

std::string lower_extension(const std::string& file) {
  std::string extension = std::filesystem::path(file).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
  return extension;
}

void read_mesh_file(JsonObject& body, BodySpec& spec, const std::string& source) {
  const std::string written = body.string("file");
  const std::string path = body.path_of("file");
  const std::string extension = lower_extension(written);
  if (extension != ".msh" && extension != ".geo")
    throw InputError(path, "= \"" + written + "\": must be a Gmsh .msh or .geo file");
  namespace fs = std::filesystem;
  fs::path file(written);
  if (file.is_relative()) file = fs::path(source).parent_path() / file;
  spec.file = file.lexically_normal().string();
  std::error_code error;
  if (!fs::is_regular_file(file, error))
    throw InputError(path, "= \"" + written + "\": no such file (looked for " + spec.file +
                               ", relative to the scene file's directory)");
  spec.mesh = MeshSpec{};
  spec.mesh.order = 0;  // the element type Gmsh makes or the file holds decides
  if (extension == ".geo") {
    if (body.has("mesh"))
      spec.mesh = read_geo_options(body.object("mesh"), spec.formulation);
    else if (spec.formulation == Formulation::Mixed)
      spec.mesh.order = kMixedOrder;
  } else {
    if (body.has("mesh"))
      throw InputError(body.path_of("mesh"),
                       "is not valid for a .msh file: the file is the mesh (its element type decides the order)");
  }
}

// "symmetry": true (every plane of the shape), false, or in 3D one plane: "x" (x = 0, the half
// x ≥ 0) or "y" (y = 0, the half y ≥ 0) — the one plane that stays a mirror under a load along
// the other axis. check_symmetry() then refuses what the scene breaks.
void read_symmetry(JsonObject& body, BodySpec& spec, int dim) {
  if (!body.has("symmetry")) return;
  const nlohmann::json& value = body.value("symmetry");
  if (value.is_boolean()) {
    spec.symmetry = value.get<bool>();
    return;
  }
  const std::string path = body.path_of("symmetry");
  if (!value.is_string())
    throw InputError(path, "= " + describe(value) +
                               (dim == 3 ? ": must be true, false, \"x\" or \"y\"" : ": must be true or false"));
  const std::string plane = value.get<std::string>();
  if (dim == 2)
    throw InputError(path, "= \"" + plane + "\": must be true or false (a 2D body has one symmetry plane, x = 0)");
  if (plane != "x" && plane != "y") unknown_choice(path, plane, "symmetry plane", {"x", "y"});
  spec.symmetry = true;
  spec.symmetry_x = plane == "x";
  spec.symmetry_y = plane == "y";
}

}  // namespace

BodySpec read_body(JsonObject body, const std::string& source, int dim) {
  BodySpec spec;
  spec.shape = body.string("shape");
  const std::vector<std::string>& shapes = dim == 2 ? kShapes2d : kShapes3d;
  if (std::find(shapes.begin(), shapes.end(), spec.shape) == shapes.end()) {
    const std::vector<std::string>& other = dim == 2 ? kShapes3d : kShapes2d;
    if (std::find(other.begin(), other.end(), spec.shape) != other.end())
      throw InputError(body.path_of("shape"),
                       "= \"" + spec.shape + "\": a " + (dim == 2 ? "3D" : "2D") + " shape, and the scene's model is " +
                           (dim == 2 ? "2D (use \"model\": \"solid\")" : "solid (3D)") + "; valid: " + join(shapes));
    unknown_choice(body.path_of("shape"), spec.shape, "shape", shapes);
  }
  if (spec.shape == "half_disc" || spec.shape == "hemisphere") {
    spec.radius = body.number("radius");
    require(spec.radius > 0, body.path_of("radius"), spec.radius, "must be positive");
  } else if (spec.shape == "rectangle" || spec.shape == "box") {
    spec.width = body.number("width");
    require(spec.width > 0, body.path_of("width"), spec.width, "must be positive");
    if (spec.shape == "box") {
      spec.depth = body.number("depth");
      require(spec.depth > 0, body.path_of("depth"), spec.depth, "must be positive");
    }
    spec.height = body.number("height");
    require(spec.height > 0, body.path_of("height"), spec.height, "must be positive");
  }
  read_symmetry(body, spec, dim);
  if (auto formulation = body.optional_string("formulation")) {
    if (*formulation == "mixed")
      spec.formulation = Formulation::Mixed;
    else if (*formulation != "displacement")
      unknown_choice(body.path_of("formulation"), *formulation, "formulation", kFormulations);
  }
  if (auto thickness = dim == 2 ? body.optional_number("thickness") : std::nullopt) {  // 3D: no thickness
    spec.thickness = *thickness;
    require(spec.thickness > 0, body.path_of("thickness"), spec.thickness, "must be positive");
  }
  if (spec.shape == "mesh") {
    read_mesh_file(body, spec, source);
  } else {
    spec.mesh = read_generated_mesh(body.object("mesh"), spec.formulation);
    if (spec.mesh.refinements != 0 && spec.shape != "half_disc" && spec.shape != "hemisphere")
      throw InputError(body.path_of("mesh.refinements"),
                       "= " + std::to_string(spec.mesh.refinements) +
                           ": only the half_disc and hemisphere shapes are refined; remove the key");
    const bool round = spec.shape == "half_disc" || spec.shape == "hemisphere";
    const double extent =
        round ? spec.radius
              : std::min(spec.width, spec.shape == "box" ? std::min(spec.depth, spec.height) : spec.height);
    require(spec.mesh.contact_size <= extent, body.path_of("mesh.contact_size"), spec.mesh.contact_size,
            "must not exceed the body's " +
                std::string(round                 ? "radius"
                            : spec.shape == "box" ? "smallest side"
                                                  : "smaller side") +
                " = " + format_value(extent));
  }
  body.finish();
  return spec;
}

}  // namespace contactqp::detail
