// Reading an input file whole (a scene, a mesh), with the one-line error a user gets when it
// cannot be read.
#pragma once

#include <string>

namespace contactqp::detail {

// The bytes of the file at `path`, or InputError naming it: "PATH is a directory, not a WHAT",
// "PATH cannot be read: No such file or directory". `what` is "scene file", "mesh file", ...
std::string read_input_file(const std::string& path, const std::string& what);

}  // namespace contactqp::detail
