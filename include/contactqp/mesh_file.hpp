// The mesh a scene's body gets, and that mesh as a Gmsh file: `contactqp mesh` meshes once, and
// a scene with "body": {"shape": "mesh", "file": ...} reuses it (a parameter study pays Gmsh once).
#pragma once

#include <string>

#include "contactqp/mesh.hpp"
#include "contactqp/model.hpp"
#include "contactqp/scene.hpp"

namespace contactqp {

// The body's mesh exactly as build_model() makes it, in the scene's own frame (before
// scene.transform turns it). InputError on a scene whose mesh cannot be made.
Mesh scene_mesh(const Scene& scene, const BuildOptions& options = {});

// Writes the mesh to `path` (a .msh file: Gmsh 4.1, binary, exact coordinates) with its named
// boundaries and points as physical groups, written to a temporary file beside it and renamed.
// Reading it back (read as a "mesh" body) gives the same nodes, elements and names. Throws
// std::runtime_error when it cannot be written, or when the mesh has named regions.
void write_mesh_file(const Mesh& mesh, const std::string& path);

}  // namespace contactqp
