// with_mid_edge_nodes() (edge_nodes.hpp): the quadratic mesh of a linear one, in 2D and 3D.
#include "edge_nodes.hpp"

namespace contactqp::detail {

Mesh with_mid_edge_nodes(const Mesh& linear, const std::vector<std::array<int, 2>>& edges, std::size_t expected_edges,
                         const SnapToBoundary& snap, NodeParents* parents) {
  Mesh quadratic;
  quadratic.dim = linear.dim;
  quadratic.order = 2;
  quadratic.nodes = linear.nodes;
  const int n_elements = linear.n_elements(), n_vertices = linear.nodes_per_element();
  quadratic.nodes.reserve(linear.nodes.size() + expected_edges);
  quadratic.elements.reserve((n_vertices + edges.size()) * static_cast<std::size_t>(n_elements));
  EdgeNodes mid(quadratic, expected_edges, parents);
  for (int e = 0; e < n_elements; ++e) {
    const int* v = linear.element(e);
    quadratic.elements.insert(quadratic.elements.end(), v, v + n_vertices);
    for (const auto& [a, b] : edges) quadratic.elements.push_back(mid(v[a], v[b]));
  }
  std::vector<std::pair<std::string, int>> new_nodes;
  for (const auto& [name, faces] : linear.boundaries) {
    auto& out = quadratic.boundaries[name];
    out.reserve(faces.size());
    for (BoundaryFace face : faces) {
      // A segment has one edge (01), a triangle three (01, 12, 20).
      const int n = face.n_nodes, n_edges = n == 2 ? 1 : 3;
      for (int k = 0; k < n_edges; ++k) {
        face.nodes[n + k] = mid(face.nodes[k], face.nodes[(k + 1) % n]);
        new_nodes.emplace_back(name, face.nodes[n + k]);
      }
      face.n_nodes = n + n_edges;
      out.push_back(face);
    }
  }
  snap_boundary_nodes(quadratic, new_nodes, snap);
  quadratic.regions = linear.regions;
  quadratic.points = linear.points;
  return quadratic;
}

}  // namespace contactqp::detail
