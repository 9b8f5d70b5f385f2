// What every use of Gmsh shares: one session at a time (Gmsh keeps global state), and the
// elements of the current Gmsh model turned into a Mesh.
#pragma once

#include <mutex>

#include "contactqp/mesh.hpp"
#include "refine.hpp"

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

// The current Gmsh model's body as a Mesh with node coordinates times `scale`: its
// tetrahedra (4- or 10-node) when a volume holds elements, a dim-3 mesh; otherwise its
// triangles (3- or 6-node), a dim-2 mesh in the plane z = 0. One order only. Only the nodes
// used by the body's elements are kept, numbered compactly in element order. When the model
// has physical groups of the body's dimension (volumes, surfaces), the body is their elements
// (as Gmsh saves a .msh); otherwise every element of that dimension. Physical groups one
// dimension down (curves in 2D, surfaces in 3D) become named boundaries (lines or 3-/6-node
// triangles of the body's order), physical groups of the body's dimension named regions,
// physical points named nodes; an unnamed group is named by its tag ("3"). The elements of
// each surface (volume) are turned positive as a whole when most are negative; an element
// that then is still negative, degenerate or (quadratic) has a Jacobian changing sign is an
// error naming its Gmsh element tag. Throws std::runtime_error. (It is mesh_from_file_data,
// mesh_file_data.hpp, on the model's contents: a .msh file read by msh_reader.cpp passes the
// same checks.)
Mesh mesh_from_gmsh(double scale = 1.0);

// The generated shapes' coarse mesh from Gmsh's (refine.hpp): without refinements the body's
// mesh itself, scaled by `radius` as it is read; with refinements read in units of the radius
// (where `snap` knows the geometry) and scaled after refining. No named regions.
CoarseMesh coarse_from_gmsh(int refinements, int order, double radius, const SnapToBoundary& snap);

// Throws std::runtime_error with Gmsh's last error message, if Gmsh logged one in this session.
void throw_if_gmsh_failed();

// Gmsh's own error text from a thrown value (Gmsh throws std::string), inside a catch block.
std::string gmsh_error_text();

}  // namespace contactqp::detail
