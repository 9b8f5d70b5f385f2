// mesh_from_file_data (mesh_file_data.hpp): the body of a Gmsh description as a Mesh, and the
// checks every body passes whatever made it — element types and order, nodes in the plane,
// orientation, degenerate and tangled elements, the names of boundaries, regions and points.
#include "mesh_file_data.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "contactqp/errors.hpp"

namespace contactqp::detail {
namespace {

// Gmsh's element types 1–19 (its manual, "MSH file format"): the linear and quadratic lines,
// triangles, quadrangles, tetrahedra, hexahedra, prisms and pyramids, and the point.
const GmshElementType kTypes[] = {
    {1, 1, 2, "2-node line"},        {2, 2, 3, "3-node triangle"},       {3, 2, 4, "4-node quadrangle"},
    {4, 3, 4, "4-node tetrahedron"}, {5, 3, 8, "8-node hexahedron"},     {6, 3, 6, "6-node prism"},
    {7, 3, 5, "5-node pyramid"},     {8, 1, 3, "3-node line"},           {9, 2, 6, "6-node triangle"},
    {10, 2, 9, "9-node quadrangle"}, {11, 3, 10, "10-node tetrahedron"}, {12, 3, 27, "27-node hexahedron"},
    {13, 3, 18, "18-node prism"},    {14, 3, 14, "14-node pyramid"},     {15, 0, 1, "point"},
    {16, 2, 8, "8-node quadrangle"}, {17, 3, 20, "20-node hexahedron"},  {18, 3, 15, "15-node prism"},
    {19, 3, 13, "13-node pyramid"},
};

constexpr int kPoint = 15;
constexpr double kLargestCoordinate = 1e100;
int line_type(int order) { return order == 1 ? 1 : 8; }
int triangle_type(int order) { return order == 1 ? 2 : 9; }
int tetrahedron_type(int order) { return order == 1 ? 4 : 11; }
int body_type(int dim, int order) { return dim == 2 ? triangle_type(order) : tetrahedron_type(order); }

std::string type_name(int type) {
  const GmshElementType* known = gmsh_element_type(type);
  return known ? known->name : "type-" + std::to_string(type);
}

using NodeIndex = std::unordered_map<std::size_t, int>;
using NodePosition = std::unordered_map<std::size_t, std::size_t>;
using Blocks = std::vector<ElementBlock>;

const Blocks& blocks_of(const MeshFileData& data, int dim, int entity) {
  static const Blocks none;
  const auto it = data.elements.find({dim, entity});
  return it == data.elements.end() ? none : it->second;
}

// The element types that have elements in an entity, each once, in block order.
std::vector<int> types_in(const MeshFileData& data, int dim, int entity) {
  std::vector<int> types;
  for (const ElementBlock& block : blocks_of(data, dim, entity))
    if (!block.tags.empty() && std::find(types.begin(), types.end(), block.type) == types.end())
      types.push_back(block.type);
  return types;
}

// The elements of `type` in one entity: their tags and their node tags, concatenated.
void elements_by_type(const MeshFileData& data, int dim, int type, int entity, std::vector<std::size_t>& tags,
                      std::vector<std::size_t>& nodes) {
  tags.clear();
  nodes.clear();
  for (const ElementBlock& block : blocks_of(data, dim, entity))
    if (block.type == type) {
      tags.insert(tags.end(), block.tags.begin(), block.tags.end());
      nodes.insert(nodes.end(), block.nodes.begin(), block.nodes.end());
    }
}

// The physical groups of one dimension: their names (the tag when unnamed) and entities.
std::vector<std::pair<std::string, std::vector<int>>> physical_groups(const MeshFileData& data, int dim) {
  std::vector<std::pair<std::string, std::vector<int>>> out;
  for (const MeshFileData::PhysicalGroup& group : data.groups)
    if (group.dim == dim) out.emplace_back(group.name.empty() ? std::to_string(group.tag) : group.name, group.entities);
  return out;
}

// The body's dimension: 3 when a volume holds elements (whatever their type: a hexahedral
// mesh is then refused by name, not read as its boundary triangles), else 2.
int body_dimension(const MeshFileData& data) {
  for (const auto& [key, blocks] : data.elements)
    if (key.first == 3)
      for (const ElementBlock& block : blocks)
        if (!block.tags.empty()) return 3;
  return 2;
}

// The element order of the body's entities: 1 or 2, never both, and no other element types
// of that dimension.
int element_order(const MeshFileData& data, int dim, const std::vector<int>& entities) {
  bool linear = false, quadratic = false;
  const char* what = dim == 2 ? "surface " : "volume ";
  for (int entity : entities) {
    for (int type : types_in(data, dim, entity)) {
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
void add_entity(Mesh& mesh, const MeshFileData& data, int entity, NodeIndex& index_of, const NodePosition& position,
                double scale, std::vector<std::size_t>& tags) {
  std::vector<std::size_t> element_tags, element_nodes;
  elements_by_type(data, mesh.dim, body_type(mesh.dim, mesh.order), entity, element_tags, element_nodes);
  const int npe = mesh.nodes_per_element();
  const bool reorder = mesh.type() == ElementType::Tet10;
  const int first = mesh.n_elements();
  for (std::size_t k = 0; k < element_nodes.size(); ++k) {
    const std::size_t tag = reorder ? element_nodes[k - k % npe + kGmshTet10[k % npe]] : element_nodes[k];
    auto [it, inserted] = index_of.emplace(tag, static_cast<int>(mesh.nodes.size()));
    if (inserted) {
      const auto found = position.find(tag);
      if (found == position.end())
        throw std::runtime_error("element " + std::to_string(element_tags[k / npe]) + " has node " +
                                 std::to_string(tag) + ", which the mesh does not define");
      const std::size_t p = found->second;
      const std::vector<double>& x = data.coordinates;
      // Stiffness, loads and gaps multiply coordinates: beyond 1e100 their products overflow.
      for (int c = 0; c < 3; ++c)
        if (!(std::abs(x[3 * p + c]) <= kLargestCoordinate))
          throw std::runtime_error("node " + std::to_string(tag) + " has a coordinate of " +
                                   format_value(x[3 * p + c]) + ", beyond ±1e100 (use other units)");
      // A 2D body keeps z = 0 exactly (its nodes' z is checked to be negligible, then dropped).
      mesh.nodes.emplace_back(scale * x[3 * p], scale * x[3 * p + 1], mesh.dim == 2 ? 0.0 : scale * x[3 * p + 2]);
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
std::vector<BoundaryFace> faces_of(const MeshFileData& data, int dim, const std::vector<int>& entities, int order,
                                   const NodeIndex& index_of, const std::string& name) {
  std::vector<BoundaryFace> faces;
  const int face_dim = dim - 1;
  const int face_type = dim == 2 ? line_type(order) : triangle_type(order);
  const int per = dim == 2 ? order + 1 : (order == 1 ? 3 : 6);
  const std::string what = dim == 2 ? "physical curve \"" : "physical surface \"";
  const std::string element = dim == 2 ? "line element" : "triangle";
  for (int entity : entities) {
    for (int type : types_in(data, face_dim, entity))
      if (type != face_type)
        throw std::runtime_error(what + name + "\" holds " + type_name(type) + " elements (Gmsh type " +
                                 std::to_string(type) + "), which do not match the order-" + std::to_string(order) +
                                 (dim == 2 ? " triangles" : " tetrahedra"));
    std::vector<std::size_t> tags, node_tags;
    elements_by_type(data, face_dim, face_type, entity, tags, node_tags);
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

const GmshElementType* gmsh_element_type(int type) {
  for (const GmshElementType& known : kTypes)
    if (known.type == type) return &known;
  return nullptr;
}

Mesh mesh_from_file_data(const MeshFileData& data, double scale) {
  Mesh mesh;
  mesh.dim = body_dimension(data);
  const auto physical_bodies = physical_groups(data, mesh.dim);
  std::vector<int> entities;
  if (physical_bodies.empty()) {
    for (const auto& [key, blocks] : data.elements)
      if (key.first == mesh.dim) entities.push_back(key.second);
  } else {
    for (const auto& [name, members] : physical_bodies) entities.insert(entities.end(), members.begin(), members.end());
    std::sort(entities.begin(), entities.end());
    entities.erase(std::unique(entities.begin(), entities.end()), entities.end());
  }
  mesh.order = element_order(data, mesh.dim, entities);

  const std::vector<std::size_t>& node_tags = data.node_tags;
  const std::vector<double>& coordinates = data.coordinates;
  NodePosition position;
  for (std::size_t k = 0; k < node_tags.size(); ++k) position[node_tags[k]] = k;
  NodeIndex index_of;
  std::vector<std::size_t> element_tags;
  std::unordered_map<int, std::pair<int, int>> elements_of_entity;  // entity -> [first, end)
  for (int entity : entities) {
    const int first = mesh.n_elements();
    add_entity(mesh, data, entity, index_of, position, scale, element_tags);
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
  for (const auto& [name, members] : physical_groups(data, mesh.dim - 1)) {
    std::vector<BoundaryFace> faces = faces_of(data, mesh.dim, members, mesh.order, index_of, name);
    auto& named = mesh.boundaries[name];
    named.insert(named.end(), faces.begin(), faces.end());
  }
  for (const auto& [name, members] : physical_groups(data, 0)) {
    for (int entity : members) {
      std::vector<std::size_t> tags, nodes;
      elements_by_type(data, 0, kPoint, entity, tags, nodes);
      if (nodes.empty()) {  // a .geo point carries its mesh node, not always a point element
        const auto it = data.point_nodes.find(entity);
        if (it != data.point_nodes.end()) nodes = it->second;
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

}  // namespace contactqp::detail
