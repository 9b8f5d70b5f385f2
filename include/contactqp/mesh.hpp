// A 2D triangle mesh with named boundaries.
#pragma once

#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

namespace contactqp {

// One edge of the boundary, oriented so that the body lies on its left: the outward normal
// is (dy, −dx)/length. `mid` is the mid-side node of a quadratic edge, −1 for a linear one.
struct BoundaryEdge {
  int a = -1, b = -1, mid = -1;
};

struct Mesh {
  std::vector<Eigen::Vector2d> nodes;  // positions (length)
  int order = 1;                       // 1: 3-node triangles; 2: 6-node (vertices, then mid-sides 01, 12, 20)
  std::vector<int> elements;           // nodes_per_element() node indices per triangle, counter-clockwise
  std::map<std::string, std::vector<BoundaryEdge>> boundaries;  // named boundary pieces
  std::map<std::string, std::vector<int>> regions;  // named sets of elements (a Gmsh mesh's physical surfaces)
  std::map<std::string, std::vector<int>> points;   // named nodes (a Gmsh mesh's physical points)

  int nodes_per_element() const { return order == 1 ? 3 : 6; }
  int n_nodes() const { return static_cast<int>(nodes.size()); }
  int n_elements() const { return static_cast<int>(elements.size()) / nodes_per_element(); }
  const int* element(int e) const { return elements.data() + e * nodes_per_element(); }
};

// The distinct nodes of a named boundary (vertices and mid-side nodes), ascending.
std::vector<int> boundary_nodes(const Mesh& mesh, const std::string& name);

// Re-orients every boundary edge so the body lies on its left. Throws std::runtime_error
// naming the first element with a defect (below), or an edge that is no element's side.
void orient(Mesh& mesh);

// Signed area of triangle e (from its vertices), > 0 when counter-clockwise.
double element_area(const Mesh& mesh, int e);

// Why element e cannot be used, or "" when it can: "degenerate" (area at most 1e-12 of
// `largest_area`), "inverted" (clockwise), or, for a 6-node triangle, a Jacobian that is not
// positive everywhere (a misplaced mid-side node). Inverted elements are an error, never
// silently flipped: a mesh whose elements disagree in orientation is tangled.
std::string element_defect(const Mesh& mesh, int e, double largest_area);
double largest_element_area(const Mesh& mesh);

// Every edge that belongs to exactly one element, oriented with the body on its left.
std::vector<BoundaryEdge> outer_boundary(const Mesh& mesh);

}  // namespace contactqp
