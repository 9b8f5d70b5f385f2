#include "gmsh_writer.hpp"

#include <gmsh.h>

#include <filesystem>
#include <numeric>
#include <stdexcept>

#include "gmsh_model.hpp"

namespace contactqp::detail {
namespace {

// Gmsh's element types (gmsh_model.cpp): points, lines, triangles, tetrahedra of each order.
constexpr int kPoint = 15;
int gmsh_type(int dim, int order) {
  if (dim == 1) return order == 1 ? 1 : 8;
  if (dim == 2) return order == 1 ? 2 : 9;
  return order == 1 ? 4 : 11;
}

// Our 10-node tetrahedron's mid-edges are 01, 12, 20, 03, 13, 23; Gmsh's 01, 12, 02, 03, 23, 13.
constexpr int kGmshTet10[10] = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};

}  // namespace

void write_gmsh_file(const Mesh& mesh, const std::string& path) {
  if (!mesh.regions.empty())
    throw std::runtime_error("the mesh has named regions; writing them to a .msh file is not supported");
  GmshSession session;
  gmsh::model::add("body");
  const int dim = mesh.dim;
  const int body = gmsh::model::addDiscreteEntity(dim);
  std::vector<std::size_t> node_tags(mesh.n_nodes());
  std::iota(node_tags.begin(), node_tags.end(), std::size_t{1});
  std::vector<double> coordinates;
  coordinates.reserve(3 * node_tags.size());
  for (const Eigen::Vector3d& x : mesh.nodes) coordinates.insert(coordinates.end(), {x.x(), x.y(), x.z()});
  gmsh::model::mesh::addNodes(dim, body, node_tags, coordinates);

  const int npe = mesh.nodes_per_element();
  const bool reorder = mesh.type() == ElementType::Tet10;
  std::vector<std::size_t> element_nodes(mesh.elements.size());
  for (std::size_t k = 0; k < element_nodes.size(); ++k)
    element_nodes[k] =
        1 + static_cast<std::size_t>(reorder ? mesh.elements[k - k % npe + kGmshTet10[k % npe]] : mesh.elements[k]);
  std::size_t next_element = 1;
  auto element_tags = [&next_element](std::size_t n) {
    std::vector<std::size_t> tags(n);
    std::iota(tags.begin(), tags.end(), next_element);
    next_element += n;
    return tags;
  };
  gmsh::model::mesh::addElementsByType(body, gmsh_type(dim, mesh.order), element_tags(mesh.n_elements()),
                                       element_nodes);
  gmsh::model::addPhysicalGroup(dim, {body});

  // Boundary faces: lines (a, b, mid) and triangles (v0 v1 v2 m01 m12 m20) are Gmsh's orders.
  for (const auto& [name, faces] : mesh.boundaries) {
    const int entity = gmsh::model::addDiscreteEntity(dim - 1);
    std::vector<std::size_t> face_nodes;
    face_nodes.reserve(faces.size() * mesh.nodes_per_face());
    for (const BoundaryFace& face : faces)
      for (int i = 0; i < face.n_nodes; ++i) face_nodes.push_back(1 + static_cast<std::size_t>(face.nodes[i]));
    gmsh::model::mesh::addElementsByType(entity, gmsh_type(dim - 1, mesh.order), element_tags(faces.size()),
                                         face_nodes);
    gmsh::model::setPhysicalName(dim - 1, gmsh::model::addPhysicalGroup(dim - 1, {entity}), name);
  }
  for (const auto& [name, nodes] : mesh.points) {
    std::vector<int> entities;
    for (int node : nodes) {
      const int entity = gmsh::model::addDiscreteEntity(0);
      gmsh::model::mesh::addElementsByType(entity, kPoint, element_tags(1), {1 + static_cast<std::size_t>(node)});
      entities.push_back(entity);
    }
    gmsh::model::setPhysicalName(0, gmsh::model::addPhysicalGroup(0, entities), name);
  }
  gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
  gmsh::option::setNumber("Mesh.Binary", 1);
  gmsh::option::setNumber("Mesh.SaveAll", 0);
  gmsh::write(path);
  throw_if_gmsh_failed();
}

}  // namespace contactqp::detail
