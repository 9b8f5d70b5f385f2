// The names a scene gives to parts of a mesh body (boundaries, regions, points) are checked
// once the mesh is read: only then are its physical groups known.
#include <cmath>

#include "../scene/json_reader.hpp"
#include "contactqp/errors.hpp"
#include "model_parts.hpp"

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
  throw InputError(field, "= \"" + name + "\": not a " + what + " of " + file + "; valid: " +
                              (list.empty() ? "none (the file names no " + what + "s)" : list) +
                              (hint.empty() ? "" : "; did you mean \"" + hint + "\"?"));
}

}  // namespace

void check_mesh_names(const Scene& scene, const Mesh& mesh) {
  if (scene.body.shape != "mesh") return;  // generated shapes were checked with the scene
  const std::string& file = scene.body.file;
  for (const LoadSpec& load : scene.loads) {
    if (!load.boundary.empty()) require_name(mesh.boundaries, load.boundary, load.path + ".boundary", "physical curve", file);
    if (!load.region.empty()) require_name(mesh.regions, load.region, load.path + ".region", "physical surface", file);
    if (!load.point.empty()) require_name(mesh.points, load.point, load.path + ".point", "physical point", file);
  }
  require_name(mesh.boundaries, scene.contact.boundary, "contact.boundary", "physical curve", file);
  if (!scene.body.symmetry) return;
  if (!mesh.boundaries.count("symmetry"))
    throw InputError("body.symmetry", "= true: " + file + " has no physical curve named \"symmetry\" (the cut x = 0)");
  // The modelled half is x ≥ 0 with its cut on x = 0.
  double extent = 0, lowest = 0;
  for (const Eigen::Vector2d& x : mesh.nodes) {
    extent = std::max(extent, x.cwiseAbs().maxCoeff());
    lowest = std::min(lowest, x.x());
  }
  for (int node : boundary_nodes(mesh, "symmetry"))
    if (std::abs(mesh.nodes[node].x()) > 1e-9 * extent)
      throw InputError("body.symmetry", "= true: the physical curve \"symmetry\" of " + file + " has a node at x = " +
                                            format_value(mesh.nodes[node].x()) + ", not on x = 0");
  if (lowest < -1e-9 * extent)
    throw InputError("body.symmetry", "= true: " + file + " reaches x = " + format_value(lowest) +
                                          " < 0; with symmetry the mesh is the half x ≥ 0");
}

}  // namespace contactqp::detail
