#include "contactqp/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <unordered_map>

namespace contactqp {
namespace {

double cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

long long edge_key(int a, int b, int n) {
  return static_cast<long long>(std::min(a, b)) * n + std::max(a, b);
}

}  // namespace

double element_area(const Mesh& mesh, int e) {
  const int* v = mesh.element(e);
  return 0.5 * cross(mesh.nodes[v[1]] - mesh.nodes[v[0]], mesh.nodes[v[2]] - mesh.nodes[v[0]]);
}

std::vector<int> boundary_nodes(const Mesh& mesh, const std::string& name) {
  std::set<int> nodes;
  auto it = mesh.boundaries.find(name);
  if (it == mesh.boundaries.end()) return {};
  for (const BoundaryEdge& edge : it->second) {
    nodes.insert(edge.a);
    nodes.insert(edge.b);
    if (edge.mid >= 0) nodes.insert(edge.mid);
  }
  return {nodes.begin(), nodes.end()};
}

void orient(Mesh& mesh) {
  const int npe = mesh.nodes_per_element();
  const int n = mesh.n_nodes();
  // Elements counter-clockwise; a degenerate one cannot be oriented and is an input error.
  double largest = 0;
  for (int e = 0; e < mesh.n_elements(); ++e) largest = std::max(largest, std::abs(element_area(mesh, e)));
  std::unordered_map<long long, int> element_of_edge;
  element_of_edge.reserve(3 * mesh.n_elements());
  for (int e = 0; e < mesh.n_elements(); ++e) {
    int* v = mesh.elements.data() + e * npe;
    const double area = element_area(mesh, e);
    if (!(std::abs(area) > 1e-12 * largest))
      throw std::runtime_error("element " + std::to_string(e) + " is degenerate (area " + std::to_string(area) + ")");
    if (area < 0) {
      std::swap(v[1], v[2]);
      if (npe == 6) std::swap(v[3], v[5]);  // mid-sides (01, 12, 20) become (02, 21, 10)
    }
    for (int k = 0; k < 3; ++k) element_of_edge[edge_key(v[k], v[(k + 1) % 3], n)] = e;
  }
  // Boundary edges with the body on their left: the element's third vertex must be on the left.
  for (auto& [name, edges] : mesh.boundaries) {
    for (BoundaryEdge& edge : edges) {
      auto it = element_of_edge.find(edge_key(edge.a, edge.b, n));
      if (it == element_of_edge.end())
        throw std::runtime_error("boundary \"" + name + "\" has an edge (" + std::to_string(edge.a) + ", " +
                                 std::to_string(edge.b) + ") that is not a side of any element");
      const int* v = mesh.element(it->second);
      int third = v[0];
      for (int k = 0; k < 3; ++k)
        if (v[k] != edge.a && v[k] != edge.b) third = v[k];
      const Eigen::Vector2d& a = mesh.nodes[edge.a];
      if (cross(mesh.nodes[edge.b] - a, mesh.nodes[third] - a) < 0) std::swap(edge.a, edge.b);
    }
  }
}

}  // namespace contactqp
