// A mesh as Gmsh describes it — entities, node and element tags, physical groups — before
// contactqp makes its Mesh of it. Two sources fill it: Gmsh's current model (gmsh_model.cpp:
// the generated shapes and .geo files, meshed by Gmsh) and a .msh file read by our own reader
// (msh_reader.cpp: versions 2.2 and 4.1, ASCII and binary). One function, mesh_from_file_data,
// then turns either into a Mesh and checks it, so a body from a file and a generated one pass
// the same checks.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "contactqp/mesh.hpp"

namespace contactqp::detail {

// The Gmsh element types contactqp knows by name: lines, triangles, quadrangles, tetrahedra,
// hexahedra, prisms, pyramids (linear and quadratic) and points. Gmsh numbers them 1–19.
struct GmshElementType {
  int type = 0;  // Gmsh's number
  int dim = 0;
  int n_nodes = 0;
  const char* name = "";  // "3-node triangle"
};
// nullptr for a type number outside the table.
const GmshElementType* gmsh_element_type(int type);

struct ElementBlock {
  int type = 0;                    // Gmsh element type
  std::vector<std::size_t> tags;   // element tags, in file order
  std::vector<std::size_t> nodes;  // node tags, gmsh_element_type(type)->n_nodes per element, Gmsh's node order
};

struct MeshFileData {
  // Node tags and their coordinates (x, y, z per node), in the order of the file or model.
  std::vector<std::size_t> node_tags;
  std::vector<double> coordinates;
  // The elements of each entity (dim, tag), block by block, in the order of the file or model.
  std::map<std::pair<int, int>, std::vector<ElementBlock>> elements;
  // The nodes Gmsh places on each point entity (dim 0), whether or not a point element holds
  // them (a .geo point carries its mesh node without one).
  std::map<int, std::vector<std::size_t>> point_nodes;
  struct PhysicalGroup {
    int dim = 0, tag = 0;
    std::string name;           // "" when the file names none (the group is then named by its tag)
    std::vector<int> entities;  // ascending tags
  };
  std::vector<PhysicalGroup> groups;  // ascending (dim, tag)
};

// The body of `data` as a Mesh with node coordinates times `scale` (see mesh_from_gmsh in
// gmsh_model.hpp for what is kept and what is an error). Throws std::runtime_error.
Mesh mesh_from_file_data(const MeshFileData& data, double scale = 1.0);

}  // namespace contactqp::detail
