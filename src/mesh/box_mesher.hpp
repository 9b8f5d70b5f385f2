// The box body (a block under a punch), meshed by Gmsh with tetrahedra graded from a fine size
// over a disc of its bottom face, where contact can happen, to a coarse size far from it.
#pragma once

#include <Eigen/Core>

#include "contactqp/mesh.hpp"
#include "graded_size.hpp"

namespace contactqp::detail {

// The body is x ∈ [−width/2, width/2], y ∈ [−depth/2, depth/2], z ∈ [0, height]; with symmetry,
// the quarter x ≥ 0, y ≥ 0 of it.
//
// The fine zone is the disc of radius fine_radius around fine_centre on the bottom face z = 0:
// the element size is contact_size on it and grows by `grading` per unit distance from it up
// to `size`, s(x) = min(size, contact_size + grading · d(x)) with d the distance to the disc
// (a flat punch of radius a is covered, rim included, by fine_radius a little above a).
struct BoxMeshRequest {
  double width = 1, depth = 1, height = 1;
  bool symmetry = false;
  // With symmetry, the cuts: both (the quarter) or one (the half x ≥ 0 or y ≥ 0).
  bool symmetry_x = true, symmetry_y = true;
  double size = 0.1;                                      // far-field element size (length)
  double contact_size = 0.01;                             // element size on the fine disc (length)
  double grading = 0.1;                                   // size growth per unit distance from the fine disc
  int order = 1;                                          // 1: 4-node tetrahedra; 2: 10-node
  Eigen::Vector2d fine_centre = Eigen::Vector2d::Zero();  // (x, y) on the bottom face (length)
  double fine_radius = 0.1;                               // length; 0 refines at the centre only
  // > 0: the circle of this radius around fine_centre is embedded in the bottom face, so
  // that mesh nodes lie on it (the rim of a flat punch, where the pressure is singular and
  // the contact zone ends); its part outside the bottom face is dropped. Length.
  double rim_radius = 0;
  VolumeAlgorithm volume_algorithm = VolumeAlgorithm::Delaunay;  // see graded_size.hpp
  // When set, the element size wanted at each point (graded_size.hpp), in place of size,
  // contact_size and grading; refinements must then be 0.
  SizeField size_field;
};

// A dim-3 Mesh with boundaries "bottom" (z = 0, inside and outside the rim alike), "top" (z = height), "left" (x = −width/2),
// "right" (x = width/2), "front" (y = −depth/2), "back" (y = depth/2); with symmetry
// "symmetry_x" (x = 0) and "symmetry_y" (y = 0) instead of "left" and "front". No regions or
// points. Throws std::runtime_error when Gmsh fails.
Mesh mesh_box(const BoxMeshRequest& request);

// The number of tetrahedra the request will give, within a factor of about 2, computed
// without meshing.
double estimate_box_elements(const BoxMeshRequest& request);

}  // namespace contactqp::detail
