// The Gmsh plugin's one exported symbol: its table of functions (gmsh_plugin.hpp). Everything
// else the plugin holds is hidden (linked with --exclude-libs,ALL).
#include "box_mesher.hpp"
#include "gmsh_model.hpp"
#include "gmsh_plugin.hpp"
#include "gmsh_writer.hpp"

namespace {

contactqp::detail::GmshPlugin make_table() {
  using namespace contactqp::detail;
  GmshPlugin table;
  table.abi = kGmshPluginAbi;
  table.coarse_half_disc = &coarse_half_disc;
  table.estimate_half_disc_triangles = &estimate_half_disc_triangles;
  table.half_disc_snap = &half_disc_snap;
  table.rectangle_sides = &rectangle_sides;
  table.mesh_rectangle = &mesh_rectangle;
  table.estimate_rectangle_triangles = &estimate_rectangle_triangles;
  table.coarse_hemisphere = &coarse_hemisphere;
  table.estimate_hemisphere_elements = &estimate_hemisphere_elements;
  table.hemisphere_snap = &hemisphere_snap;
  table.mesh_box = &mesh_box;
  table.estimate_box_elements = &estimate_box_elements;
  table.mesh_geo_file = &mesh_geo_file;
  table.write_gmsh_file = &write_gmsh_file;
  table.gmsh_error_text = &gmsh_error_text;
  return table;
}

}  // namespace

// Returns const void*, the type open_plugin() (plugins.cpp) calls it through: a call through a
// pointer to another function type is undefined (Clang's -fsanitize=function stops on it).
extern "C" __attribute__((visibility("default"))) const void* contactqp_gmsh_plugin() {
  static const contactqp::detail::GmshPlugin table = make_table();
  return &table;
}
