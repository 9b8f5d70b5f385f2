// Bodies from Gmsh files: a .msh mesh as it is, or a .geo geometry meshed by Gmsh.
#pragma once

#include <string>

#include "contactqp/mesh.hpp"

namespace contactqp::detail {

struct GmshFileRequest {
  std::string path;        // a .msh (4.1 or 2.2, ASCII or binary) or .geo file (meshed in 3D when it defines volumes)
  int order = 0;           // .geo: 1 or 2 overrides its Mesh.ElementOrder; 0 keeps it
  double size_factor = 1;  // .geo: multiplies its Mesh.MeshSizeFactor
};

// The body of the file (see mesh_from_gmsh for what is kept and what is an error). Throws
// InputError naming the file on anything that cannot be read (msh_reader.hpp), meshed (Gmsh, a
// .geo) or used.
Mesh read_gmsh_file(const GmshFileRequest& request);

// A .geo file meshed by Gmsh, in the Gmsh plugin (gmsh_plugin.hpp): read_gmsh_file() calls it
// through the plugin's table, after checking that the file can be read.
Mesh mesh_geo_file(const GmshFileRequest& request);

}  // namespace contactqp::detail
