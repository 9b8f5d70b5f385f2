// PLACEHOLDER until the Gmsh side lands (branch issue12-gmsh3d).
#pragma once
#include "contactqp/mesh.hpp"
namespace contactqp::detail {
struct HemisphereMeshRequest {
  double radius = 1;
  bool symmetry = false;
  double size = 0.1, contact_size = 0.01, grading = 0.1;
  int order = 1;
  double fine_radius = 0;
};
Mesh mesh_hemisphere(const HemisphereMeshRequest& request);
double estimate_hemisphere_elements(const HemisphereMeshRequest& request);
}  // namespace contactqp::detail
