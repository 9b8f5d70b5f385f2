// Opens a plugin on first use (plugins.hpp).
#include "plugins.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace contactqp::detail {
namespace {

namespace fs = std::filesystem;

// The folders where a plugin may be: the environment's; from the folder of the program and of
// the object holding this code (the executable, the Python module, or another plugin), the
// installed lib/contactqp/ (CMake passes the relative paths from the installed program and
// module) and that folder itself (a plugin opening another); the build tree's plugins/ (every
// program of the build runs from there); the configured install folder (a program built against
// the installed library).
std::vector<fs::path> plugin_folders() {
  std::vector<fs::path> folders;
  if (const char* dir = std::getenv("CONTACTQP_PLUGIN_DIR"); dir && *dir) folders.emplace_back(dir);
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (!error) folders.push_back((exe.parent_path() / CONTACTQP_PLUGIN_FROM_BIN).lexically_normal());
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&plugin_folders), &info) && info.dli_fname && *info.dli_fname) {
    const fs::path object = fs::absolute(info.dli_fname, error);
    if (!error && object != exe) {
      folders.push_back(object.parent_path());
      folders.push_back((object.parent_path() / CONTACTQP_PLUGIN_FROM_PYTHON).lexically_normal());
    }
  }
  folders.emplace_back(CONTACTQP_PLUGIN_BUILD_DIR);
  folders.emplace_back(CONTACTQP_PLUGIN_INSTALL_DIR);
  return folders;
}

}  // namespace

const void* open_plugin(const char* file_name, const char* symbol, int abi, const std::string& what) {
  std::string tried;
  const std::vector<fs::path> folders = plugin_folders();
  for (const fs::path& folder : folders) {
    const fs::path file = folder / file_name;
    std::error_code error;
    if (!fs::exists(file, error)) continue;
    void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      tried += "; " + std::string(dlerror());
      continue;
    }
    using Entry = const void* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, symbol));
    const void* table = entry ? entry() : nullptr;
    if (table && *static_cast<const int*>(table) == abi) return table;
    tried += "; " + file.string() + " is from another build of contactqp";
  }
  std::string list;
  for (const fs::path& folder : folders) list += (list.empty() ? "" : ", ") + folder.string();
  throw std::runtime_error(what + " is unavailable: " + file_name + " was not found in " + list + tried +
                           " (set CONTACTQP_PLUGIN_DIR to its folder)");
}

}  // namespace contactqp::detail
