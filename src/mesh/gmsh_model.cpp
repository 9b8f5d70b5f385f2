#include "gmsh_model.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace contactqp::detail {
namespace {

std::mutex gmsh_mutex;

// Gmsh element types: 15 point, 1 and 8 lines (2, 3 nodes), 2 and 9 triangles (3, 6 nodes),
// 4 and 11 tetrahedra (4, 10 nodes).
constexpr int kPoint = 15;
int line_type(int order) { return order == 1 ? 1 : 8; }
int triangle_type(int order) { return order == 1 ? 2 : 9; }
int tetrahedron_type(int order) { return order == 1 ? 4 : 11; }
int body_type(int dim, int order) { return dim == 2 ? triangle_type(order) : tetrahedron_type(order); }

using NodeIndex = std::unordered_map<std::size_t, int>;
using NodePosition = std::unordered_map<std::size_t, std::size_t>;

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

std::string type_name(int type) {
  std::string name;
  int dim, order, n_nodes, n_primary;
  std::vector<double> local;
  gmsh::model::mesh::getElementProperties(type, name, dim, order, n_nodes, local, n_primary);
  return name;
}

std::size_t nodes_of_type(int type) {
  std::string name;
  int dim, order, n_nodes, n_primary;
  std::vector<double> local;
  gmsh::model::mesh::getElementProperties(type, name, dim, order, n_nodes, local, n_primary);
  return static_cast<std::size_t>(n_nodes);
}

// The elements of `type` in one entity: their tags and their node tags, concatenated. Gmsh
// 4.8 reports one type per entity and element family (its first element's) and sizes the
// node array of getElementsByType by it, writing past its end when a later element has more
// nodes: a .msh whose volume mixes 4- and 10-node tetrahedra corrupted the heap. So the tags
// are read alone and each element's type and nodes one by one (0.03 s for 178 255 tetrahedra,
// against 0.016 s in bulk).
void elements_by_type(int type, int entity, std::vector<std::size_t>& tags, std::vector<std::size_t>& nodes) {
  std::vector<std::size_t> no_nodes;
  gmsh::model::mesh::preallocateElementsByType(type, true, false, tags, no_nodes, entity);
  if (tags.empty()) return;
  gmsh::model::mesh::getElementsByType(type, tags, no_nodes, entity);
  nodes.clear();
  nodes.reserve(tags.size() * nodes_of_type(type));
  std::vector<std::size_t> element_nodes;
  for (std::size_t tag : tags) {
    int element_type;
    gmsh::model::mesh::getElement(tag, element_type, element_nodes);
    if (element_type != type)
      throw std::runtime_error("element " + std::to_string(tag) + " is a " + type_name(element_type) + " among " +
                               type_name(type) + " elements: use one order");
    nodes.insert(nodes.end(), element_nodes.begin(), element_nodes.end());
  }
}

// The body's dimension: 3 when a volume holds elements (whatever their type: a hexahedral
// mesh is then refused by name, not read as its boundary triangles), else 2.
int body_dimension() {
  std::vector<int> types;
  gmsh::model::mesh::getElementTypes(types, 3);
  return types.empty() ? 2 : 3;
}

// The element order of the body's entities: 1 or 2, never both, and no other element types
// of that dimension.
int element_order(int dim, const std::vector<int>& entities) {
  bool linear = false, quadratic = false;
  const char* what = dim == 2 ? "surface " : "volume ";
  for (int entity : entities) {
    std::vector<int> types;
    gmsh::model::mesh::getElementTypes(types, dim, entity);
    for (int type : types) {
      if (type == body_type(dim, 1))
        linear = true;
      else if (type == body_type(dim, 2))
        quadratic = true;
      else
        throw std::runtime_error(what + std::to_string(entity) + " holds " + type_name(type) + " elements (Gmsh type " +
                                 std::to_string(type) + "): only " +
                                 (dim == 2 ? "3-node and 6-node triangles" : "4-node and 10-node tetrahedra") +
                                 " are supported");
    }
  }
  if (linear && quadratic)
    throw std::runtime_error(dim == 2 ? "it mixes 3-node and 6-node triangles: use one order"
                                      : "it mixes 4-node and 10-node tetrahedra: use one order");
  if (!linear && !quadratic)
    throw std::runtime_error(dim == 2 ? "it holds no triangles (is it meshed in 2D?)" : "it holds no tetrahedra");
  return quadratic ? 2 : 1;
}

// Where node i of our element comes in Gmsh's: the same except the 10-node tetrahedron,
// whose mid-edges Gmsh orders 01, 12, 02, 03, 23, 13 and we (as VTK) 01, 12, 20, 03, 13, 23.
// (tests/unit/test_meshers_3d.cpp checks this against Gmsh's own reference nodes.)
constexpr int kGmshTet10[10] = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};

// Elements of `entity` appended to the mesh, turned positive as a whole when most of them are
// negatively oriented (a surface whose curve loop runs clockwise); their Gmsh tags appended.
void add_entity(Mesh& mesh, int entity, NodeIndex& index_of, const NodePosition& position,
                const std::vector<double>& coordinates, double scale, std::vector<std::size_t>& tags) {
  std::vector<std::size_t> element_tags, element_nodes;
  elements_by_type(body_type(mesh.dim, mesh.order), entity, element_tags, element_nodes);
  const int npe = mesh.nodes_per_element();
  const bool reorder = mesh.type() == ElementType::Tet10;
  const int first = mesh.n_elements();
  for (std::size_t k = 0; k < element_nodes.size(); ++k) {
    const std::size_t tag = reorder ? element_nodes[k - k % npe + kGmshTet10[k % npe]] : element_nodes[k];
    auto [it, inserted] = index_of.emplace(tag, static_cast<int>(mesh.nodes.size()));
    if (inserted) {
      const std::size_t p = position.at(tag);
      // A 2D body keeps z = 0 exactly (its nodes' z is checked to be negligible, then dropped).
      mesh.nodes.emplace_back(scale * coordinates[3 * p], scale * coordinates[3 * p + 1],
                              mesh.dim == 2 ? 0.0 : scale * coordinates[3 * p + 2]);
    }
    mesh.elements.push_back(it->second);
  }
  tags.insert(tags.end(), element_tags.begin(), element_tags.end());
  int negative = 0;
  for (int e = first; e < mesh.n_elements(); ++e) negative += element_measure(mesh, e) < 0;
  if (2 * negative <= mesh.n_elements() - first) return;
  for (int e = first; e < mesh.n_elements(); ++e) flip_element(mesh.type(), mesh.elements.data() + e * npe);
}

// The faces of the physical group `name` (curves in 2D, surfaces in 3D) in terms of the body's
// nodes: lines of the body's order in 2D, triangles of it in 3D.
std::vector<BoundaryFace> faces_of(int dim, const std::vector<int>& entities, int order, const NodeIndex& index_of,
                                   const std::string& name) {
  std::vector<BoundaryFace> faces;
  const int face_dim = dim - 1;
  const int face_type = dim == 2 ? line_type(order) : triangle_type(order);
  const int per = dim == 2 ? order + 1 : (order == 1 ? 3 : 6);
  const std::string what = dim == 2 ? "physical curve \"" : "physical surface \"";
  const std::string element = dim == 2 ? "line element" : "triangle";
  for (int entity : entities) {
    std::vector<int> types;
    gmsh::model::mesh::getElementTypes(types, face_dim, entity);
    for (int type : types)
      if (type != face_type)
        throw std::runtime_error(what + name + "\" holds " + type_name(type) + " elements (Gmsh type " +
                                 std::to_string(type) + "), which do not match the order-" + std::to_string(order) +
                                 (dim == 2 ? " triangles" : " tetrahedra"));
    std::vector<std::size_t> tags, node_tags;
    elements_by_type(face_type, entity, tags, node_tags);
    for (std::size_t k = 0; k + per <= node_tags.size(); k += per) {
      BoundaryFace face;
      face.n_nodes = per;
      // Gmsh's line (a, b, mid) and 6-node triangle (v0 v1 v2 m01 m12 m20) are our orders.
      for (int i = 0; i < per; ++i) {
        auto it = index_of.find(node_tags[k + i]);
        if (it == index_of.end())
          throw std::runtime_error(what + name + "\" has a " + element + " (tag " + std::to_string(tags[k / per]) +
                                   ") whose node " + std::to_string(node_tags[k + i]) + " belongs to no " +
                                   (dim == 2 ? "triangle" : "tetrahedron") + " of the body");
        face.nodes[i] = it->second;
      }
      faces.push_back(face);
    }
  }
  return faces;
}

}  // namespace

GmshSession::GmshSession() : lock_(gmsh_mutex) {
  gmsh::initialize(0, nullptr, false);             // no user configuration files: the same mesh everywhere
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
  Mesh mesh;
  mesh.dim = body_dimension();
  gmsh::vectorpair entity_pairs;
  gmsh::model::getEntities(entity_pairs, mesh.dim);
  const auto physical_bodies = physical_groups(mesh.dim);
  std::vector<int> entities;
  if (physical_bodies.empty()) {
    for (const auto& [dim, tag] : entity_pairs) entities.push_back(tag);
  } else {
    for (const auto& [name, members] : physical_bodies) entities.insert(entities.end(), members.begin(), members.end());
    std::sort(entities.begin(), entities.end());
    entities.erase(std::unique(entities.begin(), entities.end()), entities.end());
  }
  mesh.order = element_order(mesh.dim, entities);

  std::vector<std::size_t> node_tags;
  std::vector<double> coordinates, parametric;
  gmsh::model::mesh::getNodes(node_tags, coordinates, parametric);
  NodePosition position;
  for (std::size_t k = 0; k < node_tags.size(); ++k) position[node_tags[k]] = k;
  NodeIndex index_of;
  std::vector<std::size_t> element_tags;
  std::unordered_map<int, std::pair<int, int>> elements_of_entity;  // entity -> [first, end)
  for (int entity : entities) {
    const int first = mesh.n_elements();
    add_entity(mesh, entity, index_of, position, coordinates, scale, element_tags);
    elements_of_entity[entity] = {first, mesh.n_elements()};
  }
  if (mesh.dim == 2) {
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
                               ": a 2D body must lie in the plane z = 0 (a 3D body needs its tetrahedra in the "
                               "file: with physical groups, Gmsh saves only their elements, so add a Physical Volume)");
  }
  const double largest = largest_element_measure(mesh);
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const std::string defect = element_defect(mesh, e, largest);
    if (!defect.empty()) throw std::runtime_error("element " + std::to_string(element_tags[e]) + " is " + defect);
  }

  for (const auto& [name, members] : physical_bodies) {
    std::vector<int>& region = mesh.regions[name];
    for (int entity : members)
      for (int e = elements_of_entity[entity].first; e < elements_of_entity[entity].second; ++e) region.push_back(e);
  }
  // Boundaries are the physical groups one dimension down (curves in 2D, surfaces in 3D);
  // physical curves of a 3D body name no face and are not read.
  for (const auto& [name, members] : physical_groups(mesh.dim - 1)) {
    std::vector<BoundaryFace> faces = faces_of(mesh.dim, members, mesh.order, index_of, name);
    auto& named = mesh.boundaries[name];
    named.insert(named.end(), faces.begin(), faces.end());
  }
  for (const auto& [name, members] : physical_groups(0)) {
    for (int entity : members) {
      std::vector<std::size_t> tags, nodes;
      gmsh::model::mesh::getElementsByType(kPoint, tags, nodes, entity);
      if (nodes.empty()) {  // a .geo point carries its mesh node, not always a point element
        std::vector<double> xyz, uvw;
        gmsh::model::mesh::getNodes(nodes, xyz, uvw, 0, entity);
      }
      for (std::size_t tag : nodes) {
        auto it = index_of.find(tag);
        if (it == index_of.end())
          throw std::runtime_error("physical point \"" + name + "\" (node " + std::to_string(tag) + ") belongs to no " +
                                   (mesh.dim == 2 ? "triangle" : "tetrahedron") + " of the body");
        mesh.points[name].push_back(it->second);
      }
    }
  }
  orient(mesh);
  return mesh;
}

CoarseMesh coarse_from_gmsh(int refinements, int order, double radius, const SnapToBoundary& snap) {
  CoarseMesh coarse;
  coarse.refinements = refinements;
  coarse.order = order;
  if (refinements == 0) {
    coarse.mesh = mesh_from_gmsh(radius);
  } else {
    coarse.snap = snap;
    coarse.mesh = mesh_from_gmsh(1.0);
    coarse.scale = radius;
  }
  coarse.mesh.regions.clear();  // the generated body has no named regions
  return coarse;
}

}  // namespace contactqp::detail
