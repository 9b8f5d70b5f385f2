// PLACEHOLDER until the Gmsh side lands (branch issue12-gmsh3d).
#pragma once
#include "contactqp/mesh.hpp"
namespace contactqp::detail {
struct BoxMeshRequest {
  double width = 1, depth = 1, height = 1;
  bool symmetry = false;
  double size = 0.1, contact_size = 0.01, grading = 0.1;
  int order = 1;
  double fine_radius = 0;
};
Mesh mesh_box(const BoxMeshRequest& request);
double estimate_box_elements(const BoxMeshRequest& request);
}  // namespace contactqp::detail
