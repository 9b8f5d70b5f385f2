// Gmsh, loaded when a run first meshes with it. Gmsh and what it links (OpenCASCADE, FLTK, 73
// shared libraries) took 0.16 s of every start of the program, also of the runs that never
// mesh: --version, a scene refused for a bad key, a .msh body, a QP solved from Python. So the
// code that calls Gmsh is a plugin, libcontactqp_gmsh.so, opened with dlopen on first use;
// the rest of the library reaches it only through this table. docs/architecture.md, "Plugins".
#pragma once

#include <string>
#include <vector>

#include "contactqp/mesh.hpp"
#include "mesh/box_mesher.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/half_disc_mesher.hpp"
#include "mesh/hemisphere_mesher.hpp"
#include "mesh/rectangle_mesher.hpp"

namespace contactqp::detail {

// What the plugin offers: the functions of the headers above that call Gmsh, and those of
// their files that do not but live beside them. `abi` must equal kGmshPluginAbi: a plugin
// from another build of contactqp is refused rather than called with other struct layouts.
inline constexpr int kGmshPluginAbi = 2;
struct GmshPlugin {
  int abi = 0;
  CoarseMesh (*coarse_half_disc)(const HalfDiscMeshRequest&) = nullptr;
  double (*estimate_half_disc_triangles)(const HalfDiscMeshRequest&) = nullptr;
  SnapToBoundary (*half_disc_snap)() = nullptr;
  std::vector<RectangleSide> (*rectangle_sides)(double width, double height, bool symmetry) = nullptr;
  Mesh (*mesh_rectangle)(const RectangleMeshRequest&) = nullptr;
  double (*estimate_rectangle_triangles)(const RectangleMeshRequest&) = nullptr;
  CoarseMesh (*coarse_hemisphere)(const HemisphereMeshRequest&) = nullptr;
  double (*estimate_hemisphere_elements)(const HemisphereMeshRequest&) = nullptr;
  SnapToBoundary (*hemisphere_snap)() = nullptr;
  Mesh (*mesh_box)(const BoxMeshRequest&) = nullptr;
  double (*estimate_box_elements)(const BoxMeshRequest&) = nullptr;
  Mesh (*mesh_geo_file)(const GmshFileRequest&) = nullptr;             // gmsh_reader.hpp: a .geo file
  void (*write_gmsh_file)(const Mesh&, const std::string&) = nullptr;  // gmsh_writer.hpp
  std::string (*gmsh_error_text)() = nullptr;                          // gmsh_model.hpp: inside a catch block
};

// The plugin's table, the plugin opened on the first call (thread-safe; qp/plugins.hpp says where
// it is looked for). Throws std::runtime_error "Gmsh is unavailable: ..." naming where it looked
// and why each place failed; the next call tries again.
const GmshPlugin& gmsh_plugin();

// The file name, and the symbol the plugin exports (extern "C", returning its table).
inline constexpr const char* kGmshPluginFile = "libcontactqp_gmsh.so";
inline constexpr const char* kGmshPluginSymbol = "contactqp_gmsh_plugin";

}  // namespace contactqp::detail
