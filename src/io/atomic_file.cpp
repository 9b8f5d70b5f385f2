// Output files that are never half-written: each is written to a temporary file beside its
// target and renamed over it (rename is atomic within a directory), so a reader — or a run that
// is killed — sees the previous file or the complete new one (tests/input/test_kill_write.cpp
// kills runs while they write and checks it). A killed writer leaves its temporary file behind;
// the next write of the same target removes the ones whose writer is gone.
#include "contactqp/temporary_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "contactqp/errors.hpp"
#include "contactqp/io.hpp"

namespace contactqp {

namespace fs = std::filesystem;

namespace {

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0 || name[0] == '\0') return "host";
  std::string text = name;
  for (char& c : text)
    if (c == '/' || c == '.') c = '_';
  return text;
}

// ".out.vtu.HOST-PID." — what every temporary file of `target` written by this process starts
// with; the 6 characters mkstemp picks and the suffix follow.
std::string temporary_prefix(const fs::path& target, const std::string& host, long pid) {
  return "." + target.filename().string() + "." + host + "-" + std::to_string(pid) + ".";
}

fs::path directory_of(const fs::path& target) {
  const fs::path directory = target.parent_path();
  return directory.empty() ? fs::path(".") : directory;
}

}  // namespace

void remove_abandoned_temporaries(const std::string& path, const std::string& suffix) {
  const fs::path target(path);
  const std::string host = host_name();
  const std::string start = "." + target.filename().string() + "." + host + "-";
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(directory_of(target), error)) {
    const std::string name = entry.path().filename().string();
    // .NAME.HOST-PID.XXXXXX + suffix: this host's, with a process id between.
    if (name.size() < start.size() + 8 + suffix.size() || name.compare(0, start.size(), start) != 0) continue;
    if (name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) continue;
    const std::string middle = name.substr(start.size(), name.size() - start.size() - suffix.size());
    const size_t dot = middle.find('.');
    if (dot == std::string::npos || dot == 0 || middle.size() - dot != 7) continue;
    char* end = nullptr;
    const long pid = std::strtol(middle.c_str(), &end, 10);
    if (end != middle.c_str() + dot || pid <= 0) continue;
    // The writer is gone when no process has its id (a process id reused since keeps the file:
    // harmless, it is removed later). A live writer's file is never touched.
    if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) fs::remove(entry.path(), error);
  }
}

TemporaryFile::TemporaryFile(const std::string& target, const std::string& suffix) : target_(target) {
  remove_abandoned_temporaries(target, suffix);
  const fs::path path(target);
  std::string name =
      (directory_of(path) / (temporary_prefix(path, host_name(), static_cast<long>(::getpid())) + "XXXXXX" + suffix))
          .string();
  fd_ = ::mkstemps(name.data(), static_cast<int>(suffix.size()));
  if (fd_ < 0)
    throw std::runtime_error("cannot create a file in " + directory_of(path).string() + ": " + std::strerror(errno));
  path_ = name;
  // mkstemp creates the file 0600; results are ordinary files, readable like any other.
  ::fchmod(fd_, 0644);
}

TemporaryFile::~TemporaryFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_) ::unlink(path_.c_str());
}

void TemporaryFile::write(const std::string& content) {
  // In pieces of at most 1 MiB: a file of hundreds of MB is not one system call.
  constexpr size_t kPiece = size_t(1) << 20;
  size_t written = 0;
  while (written < content.size()) {
    const ssize_t n = ::write(fd_, content.data() + written, std::min(kPiece, content.size() - written));
    if (n < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error("cannot write " + target_ + ": " + std::strerror(errno));
    }
    written += static_cast<size_t>(n);
  }
}

void TemporaryFile::commit() {
  // On disk before the name points at it, so that a crash of the machine cannot leave the new
  // name on an empty file either. A file written through path() (Gmsh) is flushed through a
  // descriptor of its own.
  int fd = fd_;
  fd_ = -1;
  if (fd < 0) fd = ::open(path_.c_str(), O_RDONLY);
  const bool synced = fd >= 0 && ::fsync(fd) == 0;
  const int reason = errno;
  const bool closed = fd >= 0 && ::close(fd) == 0;
  if (!synced || !closed)
    throw std::runtime_error("cannot write " + target_ + ": " + std::strerror(synced ? errno : reason));
  if (std::rename(path_.c_str(), target_.c_str()) != 0)
    throw std::runtime_error("cannot rename the result into " + target_ + ": " + std::strerror(errno));
  committed_ = true;
  // The rename itself reaches the disk with its directory.
  const int directory = ::open(directory_of(fs::path(target_)).c_str(), O_RDONLY | O_DIRECTORY);
  if (directory >= 0) {
    ::fsync(directory);
    ::close(directory);
  }
}

void TemporaryFile::close_descriptor() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void check_output_path(const std::string& path, const std::string& field) {
  if (path.empty()) throw InputError(field, "= \"\": an output path is required");
  std::error_code error;
  if (fs::is_directory(path, error)) throw InputError(field, "= " + path + ": is a directory, not a file");
  const fs::path directory = directory_of(fs::path(path));
  if (!fs::is_directory(directory, error))
    throw InputError(field, "= " + path + ": directory " + directory.string() + " does not exist");
  if (::access(directory.c_str(), W_OK) != 0)
    throw InputError(field, "= " + path + ": directory " + directory.string() + " is not writable");
}

void write_file_atomically(const std::string& path, const std::string& content) {
  TemporaryFile file(path);
  file.write(content);
  file.commit();
}

}  // namespace contactqp
