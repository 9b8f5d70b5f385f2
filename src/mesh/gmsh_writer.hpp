// A Mesh written as a Gmsh .msh file that read_gmsh_file() reads back as the same mesh.
#pragma once

#include <string>

#include "contactqp/mesh.hpp"

namespace contactqp::detail {

// Writes `mesh` to `path` by Gmsh (format 4.1, binary, so the coordinates are exact): the
// elements as one physical group of the body's dimension, each named boundary as a physical
// curve (2D) or surface (3D) of that name, each named point as a physical point. Node tags are
// the node indices plus one. A mesh with named regions is refused (they would need one entity
// each). Throws std::runtime_error with Gmsh's message when it cannot write.
void write_gmsh_file(const Mesh& mesh, const std::string& path);

}  // namespace contactqp::detail
