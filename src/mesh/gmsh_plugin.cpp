// Opens the Gmsh plugin on first use (gmsh_plugin.hpp), and the public mesh writer that needs it.
#include "gmsh_plugin.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "contactqp/mesh_file.hpp"
#include "contactqp/temporary_file.hpp"

namespace contactqp::detail {
namespace {

namespace fs = std::filesystem;

// The folders where the plugin may be: the environment's; from the folder of the program and of
// the object holding this code (the executable, or the Python module), the installed
// lib/contactqp/ (CMake passes the relative paths from the installed program and module); the
// build tree's plugins/ (every program of the build runs from there); the configured install
// folder (a program built against the installed library).
std::vector<fs::path> plugin_folders() {
  std::vector<fs::path> folders;
  if (const char* dir = std::getenv("CONTACTQP_PLUGIN_DIR"); dir && *dir) folders.emplace_back(dir);
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (!error) folders.push_back((exe.parent_path() / CONTACTQP_PLUGIN_FROM_BIN).lexically_normal());
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&plugin_folders), &info) && info.dli_fname && *info.dli_fname) {
    const fs::path object = fs::absolute(info.dli_fname, error);
    if (!error && object != exe)
      folders.push_back((object.parent_path() / CONTACTQP_PLUGIN_FROM_PYTHON).lexically_normal());
  }
  folders.emplace_back(CONTACTQP_PLUGIN_BUILD_DIR);
  folders.emplace_back(CONTACTQP_PLUGIN_INSTALL_DIR);
  return folders;
}

const GmshPlugin* open_plugin() {
  std::string tried;
  for (const fs::path& folder : plugin_folders()) {
    const fs::path file = folder / kGmshPluginFile;
    std::error_code error;
    if (!fs::exists(file, error)) continue;
    // RTLD_LOCAL: Gmsh's libraries (OpenCASCADE, FLTK, ...) stay out of the global symbol scope.
    void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      tried += "; " + std::string(dlerror());
      continue;
    }
    // Never closed: Gmsh keeps global state, and the sanitizers' leak report needs the
    // library still mapped at exit to name what it holds.
    using Entry = const GmshPlugin* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, kGmshPluginSymbol));
    const GmshPlugin* table = entry ? entry() : nullptr;
    if (table && table->abi == kGmshPluginAbi) return table;
    tried += "; " + file.string() + " is from another build of contactqp";
  }
  std::string folders;
  for (const fs::path& folder : plugin_folders()) folders += (folders.empty() ? "" : ", ") + folder.string();
  throw std::runtime_error(std::string("Gmsh is unavailable: ") + kGmshPluginFile + " was not found in " + folders +
                           tried + " (set CONTACTQP_PLUGIN_DIR to its folder)");
}

}  // namespace

const GmshPlugin& gmsh_plugin() {
  static std::mutex mutex;
  static const GmshPlugin* table = nullptr;
  std::lock_guard<std::mutex> lock(mutex);
  if (!table) table = open_plugin();
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
