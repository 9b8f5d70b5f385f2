// PLACEHOLDER until the Gmsh side lands (branch issue12-gmsh3d).
#include "box_mesher.hpp"
#include <stdexcept>
namespace contactqp::detail {
Mesh mesh_box(const BoxMeshRequest&) { throw std::runtime_error("not yet"); }
double estimate_box_elements(const BoxMeshRequest&) { return 0; }
}  // namespace contactqp::detail
