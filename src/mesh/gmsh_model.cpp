#include "gmsh_model.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace contactqp::detail {
namespace {

std::mutex gmsh_mutex;

// Gmsh element types: 15 point, 1 and 8 lines (2, 3 nodes), 2 and 9 triangles (3, 6 nodes).
constexpr int kPoint = 15;
int line_type(int order) { return order == 1 ? 1 : 8; }
int triangle_type(int order) { return order == 1 ? 2 : 9; }

using NodeIndex = std::unordered_map<std::size_t, int>;

std::string group_name(int dim, int tag) {
  std::string name;
  gmsh::model::getPhysicalName(dim, tag, name);
  return name.empty() ? std::to_string(tag) : name;
}

std::vector<std::pair<std::string, std::vector<int>>> physical_groups(int dim) {
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, dim);
  std::vector<std::pair<std::string, std::vector<int>>> out;
  for (const auto& [d, tag] : groups) {
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(d, tag, entities);
    out.emplace_back(group_name(d, tag), entities);
  }
  return out;
}

// The triangle order of the model: 1 or 2, never both, and no other surface elements.
int triangle_order(const std::vector<int>& surfaces) {
  bool linear = false, quadratic = false;
  for (int surface : surfaces) {
    std::vector<int> types;
    gmsh::model::mesh::getElementTypes(types, 2, surface);
    for (int type : types) {
      if (type == 2) linear = true;
      else if (type == 9) quadratic = true;
      else {
        std::string name;
        int dim, order, n_nodes, n_primary;
        std::vector<double> local;
        gmsh::model::mesh::getElementProperties(type, name, dim, order, n_nodes, local, n_primary);
        throw std::runtime_error("surface " + std::to_string(surface) + " holds " + name + " elements (Gmsh type " +
                                 std::to_string(type) + "): only 3-node and 6-node triangles are supported");
      }
    }
  }
  if (linear && quadratic) throw std::runtime_error("it mixes 3-node and 6-node triangles: use one order");
  if (!linear && !quadratic) throw std::runtime_error("it holds no triangles (is it meshed in 2D?)");
  return quadratic ? 2 : 1;
}

// Triangles of `surface` appended to the mesh, turned counter-clockwise as a whole when most
// of them are clockwise (a surface whose curve loop runs clockwise); their Gmsh tags appended.
void add_surface(Mesh& mesh, int surface, NodeIndex& index_of, const std::unordered_map<std::size_t, std::size_t>& position,
                 const std::vector<double>& coordinates, double scale, std::vector<std::size_t>& tags) {
  std::vector<std::size_t> element_tags, element_nodes;
  gmsh::model::mesh::getElementsByType(triangle_type(mesh.order), element_tags, element_nodes, surface);
  const int npe = mesh.nodes_per_element();
  const int first = mesh.n_elements();
  for (std::size_t tag : element_nodes) {
    auto [it, inserted] = index_of.emplace(tag, static_cast<int>(mesh.nodes.size()));
    if (inserted) {
      const std::size_t k = position.at(tag);
      mesh.nodes.emplace_back(scale * coordinates[3 * k], scale * coordinates[3 * k + 1]);
    }
    mesh.elements.push_back(it->second);
  }
  tags.insert(tags.end(), element_tags.begin(), element_tags.end());
  int clockwise = 0;
  for (int e = first; e < mesh.n_elements(); ++e) clockwise += element_area(mesh, e) < 0;
  if (2 * clockwise <= mesh.n_elements() - first) return;
  for (int e = first; e < mesh.n_elements(); ++e) {
    int* v = mesh.elements.data() + e * npe;
    std::swap(v[1], v[2]);
    if (npe == 6) std::swap(v[3], v[5]);  // mid-sides (01, 12, 20) become (02, 21, 10)
  }
}

std::vector<BoundaryEdge> edges_of(const std::vector<int>& curves, int order, const NodeIndex& index_of,
                                   const std::string& name) {
  std::vector<BoundaryEdge> edges;
  const int per = order == 1 ? 2 : 3;
  for (int curve : curves) {
    std::vector<int> types;
    gmsh::model::mesh::getElementTypes(types, 1, curve);
    for (int type : types)
      if (type != line_type(order))
        throw std::runtime_error("physical curve \"" + name + "\" holds line elements of Gmsh type " + std::to_string(type) +
                                 ", which do not match the order-" + std::to_string(order) + " triangles");
    std::vector<std::size_t> tags, node_tags;
    gmsh::model::mesh::getElementsByType(line_type(order), tags, node_tags, curve);
    for (std::size_t k = 0; k + per <= node_tags.size(); k += per) {
      BoundaryEdge edge;
      auto node = [&](std::size_t tag) {
        auto it = index_of.find(tag);
        if (it == index_of.end())
          throw std::runtime_error("physical curve \"" + name + "\" has a line element (tag " + std::to_string(tags[k / per]) +
                                   ") whose node " + std::to_string(tag) + " belongs to no triangle of the body");
        return it->second;
      };
      edge.a = node(node_tags[k]);
      edge.b = node(node_tags[k + 1]);
      if (order == 2) edge.mid = node(node_tags[k + 2]);
      edges.push_back(edge);
    }
  }
  return edges;
}

}  // namespace

GmshSession::GmshSession() : lock_(gmsh_mutex) {
  gmsh::initialize(0, nullptr, false);  // no user configuration files: the same mesh everywhere
  gmsh::option::setNumber("General.Terminal", 0);  // silent: contactqp reports, Gmsh does not
  gmsh::option::setNumber("General.Verbosity", 0);
  gmsh::option::setNumber("General.AbortOnError", 0);
}

void throw_if_gmsh_failed() {
  std::string error;
  gmsh::logger::getLastError(error);
  if (!error.empty()) throw std::runtime_error(error);
}

GmshSession::~GmshSession() { gmsh::finalize(); }

std::string gmsh_error_text() {
  try {
    throw;
  } catch (const std::string& text) {
    return text;
  } catch (const std::exception& error) {
    return error.what();
  } catch (...) {
    return "Gmsh failed";
  }
}

Mesh mesh_from_gmsh(double scale) {
  gmsh::vectorpair surface_pairs;
  gmsh::model::getEntities(surface_pairs, 2);
  const auto physical_surfaces = physical_groups(2);
  std::vector<int> surfaces;
  if (physical_surfaces.empty()) {
    for (const auto& [dim, tag] : surface_pairs) surfaces.push_back(tag);
  } else {
    for (const auto& [name, entities] : physical_surfaces) surfaces.insert(surfaces.end(), entities.begin(), entities.end());
    std::sort(surfaces.begin(), surfaces.end());
    surfaces.erase(std::unique(surfaces.begin(), surfaces.end()), surfaces.end());
  }
  Mesh mesh;
  mesh.order = triangle_order(surfaces);

  std::vector<std::size_t> node_tags;
  std::vector<double> coordinates, parametric;
  gmsh::model::mesh::getNodes(node_tags, coordinates, parametric);
  std::unordered_map<std::size_t, std::size_t> position;
  for (std::size_t k = 0; k < node_tags.size(); ++k) position[node_tags[k]] = k;
  NodeIndex index_of;
  std::vector<std::size_t> element_tags;
  std::unordered_map<int, std::pair<int, int>> elements_of_surface;  // surface -> [first, end)
  for (int surface : surfaces) {
    const int first = mesh.n_elements();
    add_surface(mesh, surface, index_of, position, coordinates, scale, element_tags);
    elements_of_surface[surface] = {first, mesh.n_elements()};
  }
  // A 2D body lies in the plane z = 0; a tilted or 3D surface mesh would be read wrongly.
  double extent = 0, highest = 0;
  std::size_t highest_tag = 0;
  for (const auto& [tag, index] : index_of) {
    const std::size_t k = position.at(tag);
    extent = std::max({extent, std::abs(coordinates[3 * k]), std::abs(coordinates[3 * k + 1])});
    if (std::abs(coordinates[3 * k + 2]) > highest) {
      highest = std::abs(coordinates[3 * k + 2]);
      highest_tag = tag;
    }
  }
  if (highest > 1e-9 * extent)
    throw std::runtime_error("node " + std::to_string(highest_tag) + " has z = " + std::to_string(highest) +
                             ": the body must lie in the plane z = 0");
  const double largest = largest_element_area(mesh);
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const std::string defect = element_defect(mesh, e, largest);
    if (!defect.empty()) throw std::runtime_error("element " + std::to_string(element_tags[e]) + " is " + defect);
  }

  for (const auto& [name, entities] : physical_surfaces) {
    std::vector<int>& region = mesh.regions[name];
    for (int surface : entities)
      for (int e = elements_of_surface[surface].first; e < elements_of_surface[surface].second; ++e) region.push_back(e);
  }
  for (const auto& [name, curves] : physical_groups(1)) {
    std::vector<BoundaryEdge> edges = edges_of(curves, mesh.order, index_of, name);
    auto& named = mesh.boundaries[name];
    named.insert(named.end(), edges.begin(), edges.end());
  }
  for (const auto& [name, entities] : physical_groups(0)) {
    for (int entity : entities) {
      std::vector<std::size_t> tags, nodes;
      gmsh::model::mesh::getElementsByType(kPoint, tags, nodes, entity);
      if (nodes.empty()) {  // a .geo point carries its mesh node, not always a point element
        std::vector<double> xyz, uvw;
        gmsh::model::mesh::getNodes(nodes, xyz, uvw, 0, entity);
      }
      for (std::size_t tag : nodes) {
        auto it = index_of.find(tag);
        if (it == index_of.end())
          throw std::runtime_error("physical point \"" + name + "\" (node " + std::to_string(tag) + ") belongs to no triangle of the body");
        mesh.points[name].push_back(it->second);
      }
    }
  }
  orient(mesh);
  return mesh;
}

}  // namespace contactqp::detail
