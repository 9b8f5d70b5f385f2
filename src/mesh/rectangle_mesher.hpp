// The rectangle body (a block, a strip), meshed by Gmsh with triangles graded from a fine
// size along the part of one side where contact can happen to a coarse size far from it.
#pragma once

#include <string>
#include <vector>

#include "contactqp/mesh.hpp"
#include "graded_size.hpp"

namespace contactqp::detail {

// The body is x ∈ [−width/2, width/2] (or [0, width/2] with symmetry), y ∈ [0, height].
struct RectangleMeshRequest {
  double width = 1, height = 1;
  bool symmetry = false;
  double size = 0.1;           // far-field element size (length)
  double contact_size = 0.01;  // element size along the fine part (length)
  double grading = 0.1;        // size growth per unit distance from the fine part
  int order = 1;
  std::string fine_side = "bottom";  // the side along which contact can happen
  Intervals fine;                    // the fine parts of that side, as parameters t ∈ [0, 1]
  // When set, the element size wanted at each point (graded_size.hpp), in place of size,
  // contact_size and grading; refinements must then be 0.
  SizeField size_field;
};

// One side of the rectangle, walked counter-clockwise (body on the left): x(t) = a + t (b − a).
struct RectangleSide {
  std::string name;  // "bottom", "right", "top", "left" or "symmetry"
  Eigen::Vector2d a, b;
};
std::vector<RectangleSide> rectangle_sides(double width, double height, bool symmetry);

// Boundaries of the result: one per side, named as rectangle_sides() names them.
Mesh mesh_rectangle(const RectangleMeshRequest& request);

// The number of triangles the request will give, within a factor of about 1.5.
double estimate_rectangle_triangles(const RectangleMeshRequest& request);

}  // namespace contactqp::detail
