// Opens the Gmsh plugin on first use (gmsh_plugin.hpp), and the public mesh writer that needs it.
#include "gmsh_plugin.hpp"

#include <mutex>

#include "contactqp/mesh_file.hpp"
#include "contactqp/temporary_file.hpp"
#include "qp/plugins.hpp"

namespace contactqp::detail {

const GmshPlugin& gmsh_plugin() {
  static std::mutex mutex;
  static const GmshPlugin* table = nullptr;
  std::lock_guard<std::mutex> lock(mutex);
  if (!table) table = &open_plugin_table<GmshPlugin>(kGmshPluginFile, kGmshPluginSymbol, kGmshPluginAbi, "Gmsh");
  return *table;
}

}  // namespace contactqp::detail

namespace contactqp {

void write_mesh_file(const Mesh& mesh, const std::string& path) {
  const detail::GmshPlugin& gmsh = detail::gmsh_plugin();
  // Gmsh picks the format by the extension, so the temporary file ends in .msh too.
  TemporaryFile file(path, ".msh");
  file.close_descriptor();
  gmsh.write_gmsh_file(mesh, file.path());
  file.commit();
}

}  // namespace contactqp
