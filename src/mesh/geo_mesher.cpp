// A .geo body meshed by Gmsh (part of the Gmsh plugin, gmsh_plugin.hpp).
#include <gmsh.h>

#include "contactqp/errors.hpp"
#include "gmsh_model.hpp"
#include "gmsh_reader.hpp"

namespace contactqp::detail {
namespace {

// A .geo file is meshed here, with the scene's order and size factor on top of its own
// options; a mesh the file itself made ("Mesh 2;") is remade so that those apply too. A file
// that defines volumes is meshed in 3D (tetrahedra), any other in 2D.
void mesh_geometry(const GmshFileRequest& request) {
  gmsh::model::mesh::clear();
  if (request.order > 0) gmsh::option::setNumber("Mesh.ElementOrder", request.order);
  if (request.size_factor != 1) {
    double factor = 1;
    gmsh::option::getNumber("Mesh.MeshSizeFactor", factor);
    gmsh::option::setNumber("Mesh.MeshSizeFactor", factor * request.size_factor);
  }
  gmsh::vectorpair volumes;
  gmsh::model::getEntities(volumes, 3);
  gmsh::model::mesh::generate(volumes.empty() ? 2 : 3);
  throw_if_gmsh_failed();
}

}  // namespace

Mesh mesh_geo_file(const GmshFileRequest& request) {
  GmshSession session;
  try {
    gmsh::open(request.path);
    throw_if_gmsh_failed();
    mesh_geometry(request);
  } catch (...) {
    throw InputError(request.path, "could not be meshed by Gmsh: " + gmsh_error_text());
  }
  try {
    return mesh_from_gmsh();
  } catch (const std::runtime_error& error) {
    throw InputError(request.path, std::string("cannot be used: ") + error.what());
  } catch (...) {
    throw InputError(request.path, "cannot be used: " + gmsh_error_text());
  }
}

}  // namespace contactqp::detail
