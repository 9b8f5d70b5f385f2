// The names a scene gives to parts of a mesh body (boundaries, regions, points) are checked
// once the mesh is read: only then are its physical groups known.
#include <cmath>

#include "contactqp/errors.hpp"
#include "model_parts.hpp"
#include "scene/json_reader.hpp"

namespace contactqp::detail {
namespace {

template <class Map>
void require_name(const Map& names, const std::string& name, const std::string& field, const std::string& what,
                  const std::string& file) {
  if (names.count(name)) return;
  std::vector<std::string> valid;
  for (const auto& entry : names) valid.push_back(entry.first);
  std::string list;
  for (const auto& word : valid) list += (list.empty() ? "" : ", ") + word;
  const std::string hint = nearest(name, valid);
  throw InputError(field, "= \"" + name + "\": not a " + what + " of " + file +
                              "; valid: " + (list.empty() ? "none (the file names no " + what + "s)" : list) +
                              (hint.empty() ? "" : "; did you mean \"" + hint + "\"?"));
}

}  // namespace

void check_mesh_names(const Scene& scene, const Mesh& mesh) {
  if (scene.body.shape != "mesh") return;  // generated shapes were checked with the scene
  const std::string& file = scene.body.file;
  const bool solid = mesh.dim == 3;
  const std::string boundary_group = solid ? "physical surface" : "physical curve";
  const std::string region_group = solid ? "physical volume" : "physical surface";
  for (const LoadSpec& load : scene.loads) {
    if (const std::string* boundary = load.boundary())
      require_name(mesh.boundaries, *boundary, load.path + ".boundary", boundary_group, file);
    if (const auto* gravity = load.as<GravityLoad>(); gravity && !gravity->region.empty())
      require_name(mesh.regions, gravity->region, load.path + ".region", region_group, file);
    if (const auto* point = load.as<PointLoad>(); point && !point->point.empty())
      require_name(mesh.points, point->point, load.path + ".point", "physical point", file);
  }
  require_name(mesh.boundaries, scene.contact.boundary, "contact.boundary", boundary_group, file);
  if (!scene.body.symmetry) return;
  // The modelled part is x ≥ 0 (and y ≥ 0 in 3D) with its cuts on x = 0 (and y = 0), or in 3D
  // the half beside the one plane body.symmetry names.
  double extent = 0;
  for (const Eigen::Vector3d& x : mesh.nodes) extent = std::max(extent, x.cwiseAbs().maxCoeff());
  for (const std::string& plane : symmetry_boundaries(scene.body, mesh.dim)) {
    const int c = symmetry_component(plane);
    const std::string axis = c == 0 ? "x" : "y";
    if (!mesh.boundaries.count(plane))
      throw InputError("body.symmetry", "= true: " + file + " has no " + boundary_group + " named \"" + plane +
                                            "\" (the cut " + axis + " = 0)");
    for (int node : boundary_nodes(mesh, plane))
      if (std::abs(mesh.nodes[node][c]) > 1e-9 * extent)
        throw InputError("body.symmetry", "= true: the " + boundary_group + " \"" + plane + "\" of " + file +
                                              " has a node at " + axis + " = " + format_value(mesh.nodes[node][c]) +
                                              ", not on " + axis + " = 0");
    double lowest = 0;
    for (const Eigen::Vector3d& x : mesh.nodes) lowest = std::min(lowest, x[c]);
    if (lowest < -1e-9 * extent)
      throw InputError("body.symmetry",
                       "= true: " + file + " reaches " + axis + " = " + format_value(lowest) +
                           " < 0; with symmetry the mesh is the part " +
                           (solid && symmetry_copies(scene.body, 3) == 4 ? "x ≥ 0, y ≥ 0" : axis + " ≥ 0"));
  }
}

}  // namespace contactqp::detail
