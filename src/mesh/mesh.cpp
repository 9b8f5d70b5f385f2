#include "contactqp/mesh.hpp"
#include <Eigen/Geometry>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <unordered_map>

#include "contactqp/number_format.hpp"
#include "mesh/shape_functions.hpp"

namespace contactqp {
namespace {

double cross2(const Eigen::Vector3d& u, const Eigen::Vector3d& v) { return u.x() * v.y() - u.y() * v.x(); }

// The key of a face by its sorted vertices: an edge (a, b) in 2D, a triangle (a, b, c) in 3D.
// The elements at each vertex, ascending: those at node n are element[first[n] .. first[n + 1]).
// A face of a simplex is any dim of its vertices, so the elements having a face as a side are
// the elements at its first vertex that hold the others. This replaced a hash map from faces
// to element lists, whose allocation per face took most of orient() and outer_boundary().
struct VertexElements {
  std::vector<int> first, element;
};

VertexElements vertex_elements(const Mesh& mesh) {
  const int nv = mesh.dim + 1;
  VertexElements at;
  at.first.assign(mesh.n_nodes() + 1, 0);
  for (int e = 0; e < mesh.n_elements(); ++e)
    for (int k = 0; k < nv; ++k) ++at.first[mesh.element(e)[k] + 1];
  for (int n = 0; n < mesh.n_nodes(); ++n) at.first[n + 1] += at.first[n];
  at.element.resize(at.first.back());
  std::vector<int> next(at.first.begin(), at.first.end() - 1);
  for (int e = 0; e < mesh.n_elements(); ++e)
    for (int k = 0; k < nv; ++k) at.element[next[mesh.element(e)[k]]++] = e;
  return at;
}

bool has_vertices(const Mesh& mesh, int e, const int* vertices, int n) {
  const int* v = mesh.element(e);
  for (int i = 0; i < n; ++i)
    if (std::find(v, v + mesh.dim + 1, vertices[i]) == v + mesh.dim + 1) return false;
  return true;
}

// The lowest-numbered element other than `skip` that has the face of these dim vertices as a
// side, or −1.
int element_with_face(const Mesh& mesh, const VertexElements& at, const int* vertices, int skip = -1) {
  for (int k = at.first[vertices[0]]; k < at.first[vertices[0] + 1]; ++k) {
    const int e = at.element[k];
    if (e != skip && has_vertices(mesh, e, vertices + 1, mesh.dim - 1)) return e;
  }
  return -1;
}

// Where the Jacobian of a curved quadratic element is sampled: vertices, mid-sides, centroid
// and interior points. det J is a polynomial of low degree, so a sign change shows at these
// points for every misplacement a mesher makes in practice.
const double kTriangleSamples[][2] = {
    {0, 0},     {1, 0},     {0, 1},     {0.5, 0},    {0.5, 0.5},   {0, 0.5},   {1.0 / 3, 1.0 / 3},
    {0.1, 0.1}, {0.8, 0.1}, {0.1, 0.8}, {0.45, 0.1}, {0.45, 0.45}, {0.1, 0.45}};
const double kTetrahedronSamples[][3] = {{0, 0, 0},
                                         {1, 0, 0},
                                         {0, 1, 0},
                                         {0, 0, 1},
                                         {0.5, 0, 0},
                                         {0.5, 0.5, 0},
                                         {0, 0.5, 0},
                                         {0, 0, 0.5},
                                         {0.5, 0, 0.5},
                                         {0, 0.5, 0.5},
                                         {0.25, 0.25, 0.25},
                                         {1.0 / 3, 1.0 / 3, 0},
                                         {1.0 / 3, 0, 1.0 / 3},
                                         {0, 1.0 / 3, 1.0 / 3},
                                         {1.0 / 3, 1.0 / 3, 1.0 / 3},
                                         {0.1, 0.1, 0.1},
                                         {0.7, 0.1, 0.1},
                                         {0.1, 0.7, 0.1},
                                         {0.1, 0.1, 0.7}};

double jacobian_6node(const Eigen::Vector3d* x, double xi, double eta) {
  const double L0 = 1 - xi - eta, L1 = xi, L2 = eta;
  const double dxi[] = {-(4 * L0 - 1), 4 * L1 - 1, 0, 4 * (L0 - L1), 4 * L2, -4 * L2};
  const double deta[] = {-(4 * L0 - 1), 0, 4 * L2 - 1, -4 * L1, 4 * L1, 4 * (L0 - L2)};
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
  for (int i = 0; i < 6; ++i) {
    a += dxi[i] * x[i];
    b += deta[i] * x[i];
  }
  return cross2(a, b);
}

double jacobian_10node(const Eigen::Vector3d* x, double xi, double eta, double zeta) {
  const Eigen::Matrix<double, 3, Eigen::Dynamic> dN = detail::tetrahedron_gradients(2, xi, eta, zeta);
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 10; ++i) J += dN.col(i) * x[i].transpose();
  return J.determinant();
}

}  // namespace

ElementType element_type(int dim, int order) {
  if (dim == 2) return order == 1 ? ElementType::Tri3 : ElementType::Tri6;
  return order == 1 ? ElementType::Tet4 : ElementType::Tet10;
}

int nodes_per_element(ElementType type) {
  switch (type) {
    case ElementType::Tri3:
      return 3;
    case ElementType::Tri6:
      return 6;
    case ElementType::Tet4:
      return 4;
    case ElementType::Tet10:
      return 10;
  }
  return 0;
}

std::string to_string(ElementType type) {
  switch (type) {
    case ElementType::Tri3:
      return "tri3";
    case ElementType::Tri6:
      return "tri6";
    case ElementType::Tet4:
      return "tet4";
    case ElementType::Tet10:
      return "tet10";
  }
  return "?";
}

const std::vector<std::vector<int>>& element_faces(ElementType type) {
  // Triangles: sides 01, 12, 20 (body on the left of each when counter-clockwise), with their
  // mid-sides. Tetrahedra: the faces opposite vertices 3, 2, 0, 1, counter-clockwise seen from
  // outside when (x1 − x0)·((x2 − x0) × (x3 − x0)) > 0, with the mid-edges of VTK's order.
  static const std::vector<std::vector<int>> tri3 = {{0, 1}, {1, 2}, {2, 0}};
  static const std::vector<std::vector<int>> tri6 = {{0, 1, 3}, {1, 2, 4}, {2, 0, 5}};
  static const std::vector<std::vector<int>> tet4 = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  static const std::vector<std::vector<int>> tet10 = {
      {0, 2, 1, 6, 5, 4}, {0, 1, 3, 4, 8, 7}, {1, 2, 3, 5, 9, 8}, {0, 3, 2, 7, 9, 6}};
  switch (type) {
    case ElementType::Tri3:
      return tri3;
    case ElementType::Tri6:
      return tri6;
    case ElementType::Tet4:
      return tet4;
    case ElementType::Tet10:
      return tet10;
  }
  return tri3;
}

void flip_element(ElementType type, int* v) {
  std::swap(v[1], v[2]);
  if (type == ElementType::Tri6) std::swap(v[3], v[5]);  // mid-sides (01, 12, 20) become (02, 21, 10)
  if (type == ElementType::Tet10) {
    std::swap(v[4], v[6]);  // 01 ↔ 02; 12 and 03 stay
    std::swap(v[8], v[9]);  // 13 ↔ 23
  }
}

double element_measure(const Mesh& mesh, int e) {
  const int* v = mesh.element(e);
  const Eigen::Vector3d& x0 = mesh.nodes[v[0]];
  if (mesh.dim == 2) return 0.5 * cross2(mesh.nodes[v[1]] - x0, mesh.nodes[v[2]] - x0);
  return (mesh.nodes[v[1]] - x0).dot((mesh.nodes[v[2]] - x0).cross(mesh.nodes[v[3]] - x0)) / 6.0;
}

double element_area(const Mesh& mesh, int e) { return element_measure(mesh, e); }

double largest_element_measure(const Mesh& mesh) {
  double largest = 0;
  for (int e = 0; e < mesh.n_elements(); ++e) largest = std::max(largest, std::abs(element_measure(mesh, e)));
  return largest;
}

double largest_element_area(const Mesh& mesh) { return largest_element_measure(mesh); }

std::string element_defect(const Mesh& mesh, int e, double largest_measure) {
  const double measure = element_measure(mesh, e);
  const std::string what = mesh.dim == 2 ? "area " : "volume ";
  if (!(std::abs(measure) > 1e-12 * largest_measure)) return "degenerate (" + what + std::to_string(measure) + ")";
  if (measure < 0)
    return "inverted (" + std::string(mesh.dim == 2 ? "clockwise, " : "negatively oriented, ") + what +
           std::to_string(measure) + ")";
  if (mesh.order == 2) {
    const int* v = mesh.element(e);
    const int npe = mesh.nodes_per_element();
    Eigen::Vector3d x[10];
    for (int i = 0; i < npe; ++i) x[i] = mesh.nodes[v[i]];
    if (mesh.dim == 2) {
      for (const auto& p : kTriangleSamples)
        if (!(jacobian_6node(x, p[0], p[1]) > 0))
          return "inverted (its Jacobian is not positive at (ξ, η) = (" + number(p[0]) + ", " + number(p[1]) +
                 "): a mid-side node is misplaced)";
    } else {
      for (const auto& p : kTetrahedronSamples)
        if (!(jacobian_10node(x, p[0], p[1], p[2]) > 0))
          return "inverted (its Jacobian is not positive at (ξ, η, ζ) = (" + number(p[0]) + ", " + number(p[1]) + ", " +
                 number(p[2]) + "): a mid-edge node is misplaced)";
    }
  }
  return "";
}

std::vector<int> boundary_nodes(const Mesh& mesh, const std::string& name) {
  std::set<int> nodes;
  auto it = mesh.boundaries.find(name);
  if (it == mesh.boundaries.end()) return {};
  for (const BoundaryFace& face : it->second)
    for (int k = 0; k < face.n_nodes; ++k) nodes.insert(face.nodes[k]);
  return {nodes.begin(), nodes.end()};
}

Eigen::Vector3d face_normal(const Mesh& mesh, const BoundaryFace& face) {
  const Eigen::Vector3d& a = mesh.nodes[face.nodes[0]];
  const Eigen::Vector3d& b = mesh.nodes[face.nodes[1]];
  if (mesh.dim == 2) {
    const Eigen::Vector3d t = b - a;
    return Eigen::Vector3d(t.y(), -t.x(), 0.0).normalized();  // body on the left
  }
  return (b - a).cross(mesh.nodes[face.nodes[2]] - a).normalized();
}

namespace {

// Turns a face around (its normal reverses): in 2D a ↔ b; in 3D vertices 1 ↔ 2 with the
// mid-sides (01, 12, 20) becoming (02, 21, 10).
void flip_face(int dim, BoundaryFace& face) {
  if (dim == 2) {
    std::swap(face.nodes[0], face.nodes[1]);
    return;
  }
  std::swap(face.nodes[1], face.nodes[2]);
  if (face.n_nodes == 6) std::swap(face.nodes[3], face.nodes[5]);
}

}  // namespace

void orient(Mesh& mesh) {
  const double largest = largest_element_measure(mesh);
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const std::string defect = element_defect(mesh, e, largest);
    if (!defect.empty()) throw std::runtime_error("element " + std::to_string(e) + " is " + defect);
  }
  const VertexElements at = vertex_elements(mesh);
  const int nv = mesh.nodes_per_element() == 3 || mesh.nodes_per_element() == 6 ? 3 : 4;  // vertices per element
  // A boundary face points outwards when the element's remaining vertex lies behind it.
  for (auto& [name, faces] : mesh.boundaries) {
    for (BoundaryFace& face : faces) {
      const int element =
          face.nodes[0] >= 0 && face.nodes[0] < mesh.n_nodes() ? element_with_face(mesh, at, face.nodes.data()) : -1;
      if (element < 0) {
        std::string nodes;
        for (int k = 0; k < mesh.dim; ++k) nodes += (k ? ", " : "") + std::to_string(face.nodes[k]);
        throw std::runtime_error("boundary \"" + name + "\" has a " + (mesh.dim == 2 ? "edge" : "face") + " (" + nodes +
                                 ") that is not a side of any element");
      }
      const int* v = mesh.element(element);
      int other = v[0];
      for (int k = 0; k < nv; ++k)
        if (std::find(face.nodes.begin(), face.nodes.begin() + mesh.dim, v[k]) == face.nodes.begin() + mesh.dim)
          other = v[k];
      const Eigen::Vector3d& a = mesh.nodes[face.nodes[0]];
      const double side =
          mesh.dim == 2
              ? cross2(mesh.nodes[face.nodes[1]] - a, mesh.nodes[other] - a)
              : -(mesh.nodes[face.nodes[1]] - a).cross(mesh.nodes[face.nodes[2]] - a).dot(mesh.nodes[other] - a);
      if (side < 0) flip_face(mesh.dim, face);
    }
  }
}

std::vector<BoundaryFace> outer_boundary(const Mesh& mesh) {
  std::vector<BoundaryFace> out;
  const VertexElements at = vertex_elements(mesh);
  const auto& faces = element_faces(mesh.type());
  const int per_face = mesh.nodes_per_face();
  int vertices[3];
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    for (const auto& local : faces) {
      for (int k = 0; k < mesh.dim; ++k) vertices[k] = v[local[k]];
      if (element_with_face(mesh, at, vertices, e) >= 0) continue;  // an inner face
      BoundaryFace face;
      face.n_nodes = per_face;
      for (int k = 0; k < per_face; ++k) face.nodes[k] = v[local[k]];
      out.push_back(face);
    }
  }
  return out;
}

}  // namespace contactqp
