// PLACEHOLDER until the Gmsh side lands (branch issue12-gmsh3d).
#include "hemisphere_mesher.hpp"
#include <stdexcept>
namespace contactqp::detail {
Mesh mesh_hemisphere(const HemisphereMeshRequest&) { throw std::runtime_error("not yet"); }
double estimate_hemisphere_elements(const HemisphereMeshRequest&) { return 0; }
}  // namespace contactqp::detail
