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

// Where the Jacobian of a curved 6-node triangle is sampled: vertices, mid-sides, centroid
// and interior points. det J is quadratic in (ξ, η), so a sign change shows at these points
// for every misplacement a mesher makes in practice.
const double kSamples[][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}, {1.0 / 3, 1.0 / 3},
                              {0.1, 0.1}, {0.8, 0.1}, {0.1, 0.8}, {0.45, 0.1}, {0.45, 0.45}, {0.1, 0.45}};

double jacobian_6node(const Eigen::Vector2d* x, double xi, double eta) {
  const double L0 = 1 - xi - eta, L1 = xi, L2 = eta;
  const double dxi[] = {-(4 * L0 - 1), 4 * L1 - 1, 0, 4 * (L0 - L1), 4 * L2, -4 * L2};
  const double deta[] = {-(4 * L0 - 1), 0, 4 * L2 - 1, -4 * L1, 4 * L1, 4 * (L0 - L2)};
  Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();
  for (int i = 0; i < 6; ++i) {
    a += dxi[i] * x[i];
    b += deta[i] * x[i];
  }
  return cross(a, b);
}

// For each undirected edge, the elements that have it as a side.
std::unordered_map<long long, std::vector<int>> elements_of_edges(const Mesh& mesh) {
  std::unordered_map<long long, std::vector<int>> map;
  map.reserve(3 * mesh.n_elements());
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    for (int k = 0; k < 3; ++k) map[edge_key(v[k], v[(k + 1) % 3], mesh.n_nodes())].push_back(e);
  }
  return map;
}

}  // namespace

double element_area(const Mesh& mesh, int e) {
  const int* v = mesh.element(e);
  return 0.5 * cross(mesh.nodes[v[1]] - mesh.nodes[v[0]], mesh.nodes[v[2]] - mesh.nodes[v[0]]);
}

double largest_element_area(const Mesh& mesh) {
  double largest = 0;
  for (int e = 0; e < mesh.n_elements(); ++e) largest = std::max(largest, std::abs(element_area(mesh, e)));
  return largest;
}

std::string element_defect(const Mesh& mesh, int e, double largest_area) {
  const double area = element_area(mesh, e);
  if (!(std::abs(area) > 1e-12 * largest_area)) return "degenerate (area " + std::to_string(area) + ")";
  if (area < 0) return "inverted (clockwise, area " + std::to_string(area) + ")";
  if (mesh.order == 2) {
    const int* v = mesh.element(e);
    Eigen::Vector2d x[6];
    for (int i = 0; i < 6; ++i) x[i] = mesh.nodes[v[i]];
    for (const auto& p : kSamples)
      if (!(jacobian_6node(x, p[0], p[1]) > 0))
        return "inverted (its Jacobian is not positive at (ξ, η) = (" + std::to_string(p[0]) + ", " +
               std::to_string(p[1]) + "): a mid-side node is misplaced)";
  }
  return "";
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
  const double largest = largest_element_area(mesh);
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const std::string defect = element_defect(mesh, e, largest);
    if (!defect.empty()) throw std::runtime_error("element " + std::to_string(e) + " is " + defect);
  }
  const auto element_of_edge = elements_of_edges(mesh);
  // Boundary edges with the body on their left: the element's third vertex must be on the left.
  for (auto& [name, edges] : mesh.boundaries) {
    for (BoundaryEdge& edge : edges) {
      auto it = element_of_edge.find(edge_key(edge.a, edge.b, mesh.n_nodes()));
      if (it == element_of_edge.end())
        throw std::runtime_error("boundary \"" + name + "\" has an edge (" + std::to_string(edge.a) + ", " +
                                 std::to_string(edge.b) + ") that is not a side of any element");
      const int* v = mesh.element(it->second.front());
      int third = v[0];
      for (int k = 0; k < 3; ++k)
        if (v[k] != edge.a && v[k] != edge.b) third = v[k];
      const Eigen::Vector2d& a = mesh.nodes[edge.a];
      if (cross(mesh.nodes[edge.b] - a, mesh.nodes[third] - a) < 0) std::swap(edge.a, edge.b);
    }
  }
}

std::vector<BoundaryEdge> outer_boundary(const Mesh& mesh) {
  std::vector<BoundaryEdge> edges;
  const auto element_of_edge = elements_of_edges(mesh);
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    for (int k = 0; k < 3; ++k) {
      const int a = v[k], b = v[(k + 1) % 3];
      if (element_of_edge.at(edge_key(a, b, mesh.n_nodes())).size() != 1) continue;
      // Counter-clockwise elements have the body on the left of (a, b); mid-sides 01, 12, 20.
      edges.push_back({a, b, mesh.order == 2 ? v[3 + k] : -1});
    }
  }
  return edges;
}

}  // namespace contactqp
