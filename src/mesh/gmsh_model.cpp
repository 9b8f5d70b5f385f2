#include "gmsh_model.hpp"

#include <gmsh.h>

#include <stdexcept>

#include "mesh_file_data.hpp"

namespace contactqp::detail {
namespace {

std::mutex gmsh_mutex;

std::string gmsh_type_name(int type) {
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
      throw std::runtime_error("element " + std::to_string(tag) + " is a " + gmsh_type_name(element_type) + " among " +
                               gmsh_type_name(type) + " elements: use one order");
    nodes.insert(nodes.end(), element_nodes.begin(), element_nodes.end());
  }
}

// Gmsh's current model as a MeshFileData: every entity with its elements, type by type, the
// nodes of the point entities, the physical groups with their names.
MeshFileData data_from_gmsh() {
  MeshFileData data;
  std::vector<double> parametric;
  gmsh::model::mesh::getNodes(data.node_tags, data.coordinates, parametric);
  for (int dim = 0; dim <= 3; ++dim) {
    gmsh::vectorpair entities;
    gmsh::model::getEntities(entities, dim);
    for (const auto& [d, tag] : entities) {
      std::vector<ElementBlock>& blocks = data.elements[{d, tag}];
      std::vector<int> types;
      gmsh::model::mesh::getElementTypes(types, d, tag);
      for (int type : types) {
        ElementBlock block;
        block.type = type;
        elements_by_type(type, tag, block.tags, block.nodes);
        blocks.push_back(std::move(block));
      }
      if (d == 0) {
        std::vector<double> xyz, uvw;
        gmsh::model::mesh::getNodes(data.point_nodes[tag], xyz, uvw, 0, tag);
      }
    }
    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups, dim);
    for (const auto& [d, tag] : groups) {
      MeshFileData::PhysicalGroup group;
      group.dim = d;
      group.tag = tag;
      gmsh::model::getPhysicalName(d, tag, group.name);
      gmsh::model::getEntitiesForPhysicalGroup(d, tag, group.entities);
      data.groups.push_back(std::move(group));
    }
  }
  return data;
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

GmshSession::~GmshSession() {
  gmsh::model::mesh::removeSizeCallback();  // set_size_field()'s, which holds the caller's field
  gmsh::finalize();
}

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

Mesh mesh_from_gmsh(double scale) { return mesh_from_file_data(data_from_gmsh(), scale); }

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
