#include "gmsh_reader.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "contactqp/errors.hpp"
#include "gmsh_model.hpp"
#include "msh_reader.hpp"

namespace contactqp::detail {
namespace {

bool is_geo(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
  return extension == ".geo";
}

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

Mesh read_gmsh_file(const GmshFileRequest& request) {
  // Gmsh opens a missing file as an empty model without a word: check first.
  if (!std::ifstream(request.path))
    throw InputError(request.path, "cannot be read: " + std::string(std::strerror(errno)));
  if (!is_geo(request.path)) {
    // A .msh is read by our own reader (msh_reader.hpp says why), never by Gmsh.
    const MeshFileData data = read_msh_file(request.path);
    try {
      return mesh_from_file_data(data);
    } catch (const std::runtime_error& error) {
      throw InputError(request.path, std::string("cannot be used: ") + error.what());
    }
  }
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
