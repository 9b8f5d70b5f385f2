// The temporary file an output is written to before it is renamed over its target
// (write_file_atomically, io.hpp; the Gmsh mesh writer, which needs a path to write to).
#pragma once

#include <string>

namespace contactqp {

// A new file beside `target`, named .TARGET.HOST-PID.XXXXXX + suffix (hidden, unique, and
// telling which process writes it), created 0644. commit() flushes it to disk and renames it
// over the target; if it is never committed, the destructor removes it. A process killed
// before commit() leaves it behind: the next TemporaryFile of the same target removes every
// such file whose writer no longer runs on this host.
class TemporaryFile {
 public:
  explicit TemporaryFile(const std::string& target, const std::string& suffix = "");
  ~TemporaryFile();
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  const std::string& path() const { return path_; }
  void write(const std::string& content);  // appends; std::runtime_error naming the target on failure
  // For a writer that opens path() itself (Gmsh): our descriptor is closed first.
  void close_descriptor();
  void commit();  // std::runtime_error naming the target on failure

 private:
  std::string target_, path_;
  int fd_ = -1;
  bool committed_ = false;
};

// Removes the temporary files of `target` (with `suffix`) left by writers that are gone.
void remove_abandoned_temporaries(const std::string& target, const std::string& suffix = "");

}  // namespace contactqp
