// What every use of Gmsh shares: one session at a time (Gmsh keeps global state), and the
// triangles of the current Gmsh model turned into a Mesh.
#pragma once

#include <mutex>

#include "contactqp/mesh.hpp"

namespace contactqp::detail {

// Holds the process-wide Gmsh lock and a freshly initialised, silent Gmsh for its lifetime.
// Gmsh is told not to throw on errors: an exception thrown from inside its .geo parser leaves
// the parser's global state broken for every later .geo in the process. Errors are read back
// with throw_if_gmsh_failed() instead.
class GmshSession {
 public:
  GmshSession();
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  std::lock_guard<std::mutex> lock_;
};

// The current Gmsh model's triangles (3-node or 6-node; one order only) as a Mesh with node
// coordinates times `scale`. Only the nodes used by triangles are kept, numbered compactly.
// When the model has physical surfaces, the body is their triangles (as Gmsh saves a .msh);
// otherwise every triangle. Physical curves become named boundaries, physical surfaces
// named regions, physical points named nodes; an unnamed group is named by its tag ("3").
// The elements of each surface are turned counter-clockwise as a whole; an element that then
// is still clockwise, degenerate or (6-node) has a Jacobian changing sign is an error naming
// its Gmsh element tag. Throws std::runtime_error.
Mesh mesh_from_gmsh(double scale = 1.0);

// Throws std::runtime_error with Gmsh's last error message, if Gmsh logged one in this session.
void throw_if_gmsh_failed();

// Gmsh's own error text from a thrown value (Gmsh throws std::string), inside a catch block.
std::string gmsh_error_text();

}  // namespace contactqp::detail
