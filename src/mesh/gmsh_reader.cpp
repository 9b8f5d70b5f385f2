// A body's mesh file: a .msh read by our own reader, a .geo meshed by Gmsh in the plugin
// (gmsh_plugin.hpp), so that a run from a .msh never loads Gmsh.
#include "gmsh_reader.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "contactqp/errors.hpp"
#include "gmsh_plugin.hpp"
#include "mesh_file_data.hpp"
#include "msh_reader.hpp"

namespace contactqp::detail {
namespace {

bool is_geo(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
  return extension == ".geo";
}

}  // namespace

Mesh read_gmsh_file(const GmshFileRequest& request) {
  // Gmsh opens a missing file as an empty model without a word: check first.
  if (!std::ifstream(request.path))
    throw InputError(request.path, "cannot be read: " + std::string(std::strerror(errno)));
  if (is_geo(request.path)) return gmsh_plugin().mesh_geo_file(request);
  // A .msh is read by our own reader (msh_reader.hpp says why), never by Gmsh.
  const MeshFileData data = read_msh_file(request.path);
  try {
    return mesh_from_file_data(data);
  } catch (const std::runtime_error& error) {
    throw InputError(request.path, std::string("cannot be used: ") + error.what());
  }
}

}  // namespace contactqp::detail
