// The mesh of one body, in 2D or 3D: nodes, elements of one type, named boundary faces.
//
// One Mesh for every dimension (docs/architecture.md, "One FE core for 2D and 3D"): `dim` and
// `order` are run-time properties and decide the element type — 3- or 6-node triangles in 2D,
// 4- or 10-node tetrahedra in 3D. Node positions are stored as 3-vectors with z = 0 in 2D (as
// MFEM stores its vertices and VTK its points), so geometry outside the element kernels is
// written once; the kernels read the first `dim` components into fixed-size matrices.
#pragma once

#include <Eigen/Core>
#include <array>
#include <map>
#include <string>
#include <vector>

namespace contactqp {

enum class ElementType {
  Tri3,   // 3-node triangle
  Tri6,   // 6-node triangle: vertices, then mid-sides 01, 12, 20
  Tet4,   // 4-node tetrahedron
  Tet10,  // 10-node tetrahedron: vertices, then mid-edges 01, 12, 20, 03, 13, 23 (VTK's order)
};

ElementType element_type(int dim, int order);
int nodes_per_element(ElementType type);
std::string to_string(ElementType type);  // "tri3", "tri6", "tet4", "tet10"

// One face of the boundary: an edge in 2D (a, b, then the mid-side node when quadratic), a
// triangle in 3D (three vertices, then the mid-sides 01, 12, 20 when quadratic). Oriented so
// that its normal points out of the body: in 2D the body lies on the left of a → b (outward
// normal (dy, −dx)/length); in 3D the vertices run counter-clockwise seen from outside
// (outward normal along (x1 − x0) × (x2 − x0)).
struct BoundaryFace {
  std::array<int, 6> nodes{{-1, -1, -1, -1, -1, -1}};
  int n_nodes = 0;  // 2 or 3 (2D), 3 or 6 (3D)

  int n_vertices(int dim) const { return dim; }
  int node(int k) const { return nodes[k]; }
};

struct Mesh {
  int dim = 2;                         // 2: triangles in the plane z = 0; 3: tetrahedra
  int order = 1;                       // 1: linear elements; 2: quadratic (isoparametric)
  std::vector<Eigen::Vector3d> nodes;  // positions (length); z = 0 in 2D
  std::vector<int> elements;           // nodes_per_element() node indices per element, positively oriented
  std::map<std::string, std::vector<BoundaryFace>> boundaries;  // named boundary pieces
  std::map<std::string, std::vector<int>>
      regions;  // named sets of elements (a Gmsh mesh's physical groups of dimension dim)
  std::map<std::string, std::vector<int>> points;  // named nodes (a Gmsh mesh's physical points)

  ElementType type() const { return element_type(dim, order); }
  int nodes_per_element() const { return contactqp::nodes_per_element(type()); }
  int nodes_per_face() const { return dim == 2 ? order + 1 : (order == 1 ? 3 : 6); }
  int n_nodes() const { return static_cast<int>(nodes.size()); }
  int n_elements() const { return static_cast<int>(elements.size()) / nodes_per_element(); }
  int n_dofs() const { return dim * n_nodes(); }  // DOF d = dim·node + component
  const int* element(int e) const { return elements.data() + e * nodes_per_element(); }
};

// The distinct nodes of a named boundary (vertices and mid-side nodes), ascending.
std::vector<int> boundary_nodes(const Mesh& mesh, const std::string& name);

// Re-orients every boundary face so that its normal points out of the body. Throws
// std::runtime_error naming the first element with a defect (below), or a face that is no
// element's side.
void orient(Mesh& mesh);

// Signed measure of element e from its vertices: area (2D, > 0 counter-clockwise) or volume
// (3D, > 0 when (x1 − x0)·((x2 − x0) × (x3 − x0)) > 0).
double element_measure(const Mesh& mesh, int e);
double element_area(const Mesh& mesh, int e);  // the same, by its 2D name

// Why element e cannot be used, or "" when it can: "degenerate" (measure at most 1e-12 of
// `largest_measure`), "inverted" (negatively oriented), or, for a quadratic element, a
// Jacobian that is not positive everywhere (a misplaced mid-side node). Inverted elements are
// an error, never silently flipped: a mesh whose elements disagree in orientation is tangled.
std::string element_defect(const Mesh& mesh, int e, double largest_measure);
double largest_element_measure(const Mesh& mesh);
double largest_element_area(const Mesh& mesh);  // the same, by its 2D name

// Every face that belongs to exactly one element, oriented outwards, in element order.
std::vector<BoundaryFace> outer_boundary(const Mesh& mesh);

// The local faces of an element type, oriented outwards for a positively oriented element:
// node positions within the element (vertices first, then mid-sides), nodes_per_face each.
const std::vector<std::vector<int>>& element_faces(ElementType type);

// A face's unit outward normal from its vertices (2D: of the chord a → b).
Eigen::Vector3d face_normal(const Mesh& mesh, const BoundaryFace& face);

// Turns the element's orientation (swaps two vertices and the mid-sides that go with them).
void flip_element(ElementType type, int* nodes);

}  // namespace contactqp
