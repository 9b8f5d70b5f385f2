#include "scene/input_file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "contactqp/errors.hpp"

namespace contactqp::detail {

std::string read_input_file(const std::string& path, const std::string& what) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw InputError(path, "is a directory, not a " + what);
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path, "cannot be read: " + std::string(std::strerror(errno)));
  std::ostringstream bytes;
  bytes << file.rdbuf();
  if (file.bad()) throw InputError(path, "cannot be read");
  return bytes.str();
}

}  // namespace contactqp::detail
