#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "contactqp/errors.hpp"
#include "contactqp/io.hpp"

namespace contactqp {

namespace fs = std::filesystem;

void check_output_path(const std::string& path, const std::string& field) {
  if (path.empty()) throw InputError(field, "= \"\": an output path is required");
  std::error_code error;
  if (fs::is_directory(path, error)) throw InputError(field, "= " + path + ": is a directory, not a file");
  fs::path directory = fs::path(path).parent_path();
  if (directory.empty()) directory = ".";
  if (!fs::is_directory(directory, error))
    throw InputError(field, "= " + path + ": directory " + directory.string() + " does not exist");
  if (::access(directory.c_str(), W_OK) != 0)
    throw InputError(field, "= " + path + ": directory " + directory.string() + " is not writable");
}

std::string write_temporary_file(const std::string& path, const std::string& content) {
  const fs::path target(path);
  fs::path directory = target.parent_path();
  if (directory.empty()) directory = ".";
  std::string temporary = (directory / ("." + target.filename().string() + ".XXXXXX")).string();
  const int fd = ::mkstemp(temporary.data());
  if (fd < 0) throw std::runtime_error("cannot create a file in " + directory.string() + ": " + std::strerror(errno));
  size_t written = 0;
  while (written < content.size()) {
    const ssize_t n = ::write(fd, content.data() + written, content.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string reason = std::strerror(errno);
      ::close(fd);
      ::unlink(temporary.c_str());
      throw std::runtime_error("cannot write " + path + ": " + reason);
    }
    written += static_cast<size_t>(n);
  }
  // mkstemp creates the file 0600; results are ordinary files, readable like any other.
  ::fchmod(fd, 0644);
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    ::unlink(temporary.c_str());
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  }
  return temporary;
}

void commit_temporary_file(const std::string& temporary, const std::string& path) {
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    ::unlink(temporary.c_str());
    throw std::runtime_error("cannot rename the result into " + path + ": " + reason);
  }
}

void discard_temporary_file(const std::string& temporary) { ::unlink(temporary.c_str()); }

void write_file_atomically(const std::string& path, const std::string& content) {
  commit_temporary_file(write_temporary_file(path, content), path);
}

}  // namespace contactqp
