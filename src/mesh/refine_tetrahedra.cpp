// Uniform refinement of 4-node tetrahedra (refine.hpp): each into eight, then mid-edge nodes.
#include <array>
#include <stdexcept>

#include "edge_nodes.hpp"
#include "refine.hpp"

namespace contactqp::detail {
namespace {

// A tetrahedron's ten nodes as they are numbered here: its vertices 0–3, then the new
// mid-edge nodes 01, 12, 20, 03, 13, 23 (the 10-node tetrahedron's order).
constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};

// The children, each positively oriented when the parent is (tests/unit/test_refine_tetrahedra.cpp
// checks them on the reference tetrahedron): each corner tetrahedron is the parent shrunk by
// half about a vertex; the octahedron of the six mid-edge nodes is cut along one of its three
// diagonals (01–23, 20–13 or 03–12) into four tetrahedra around it.
constexpr int kCorners[4][4] = {{0, 4, 6, 7}, {4, 1, 5, 8}, {6, 5, 2, 9}, {7, 8, 9, 3}};
constexpr int kDiagonals[3][2] = {{4, 9}, {6, 8}, {7, 5}};
constexpr int kOctahedron[3][4][4] = {
    {{4, 9, 6, 7}, {4, 9, 7, 8}, {4, 9, 8, 5}, {4, 9, 5, 6}},
    {{6, 8, 7, 4}, {6, 8, 9, 7}, {6, 8, 5, 9}, {6, 8, 4, 5}},
    {{7, 5, 4, 6}, {7, 5, 6, 9}, {7, 5, 9, 8}, {7, 5, 8, 4}},
};

// About 1.2 edges per tetrahedron in a Delaunay mesh: the hash table is sized once.
std::size_t expected_edges(int n_elements) { return 5 * static_cast<std::size_t>(n_elements) / 4 + 64; }

// Each boundary triangle's three new mid-edge nodes, listed for snapping under its boundary.
void list_face_nodes(const std::string& name, const BoundaryFace& face, EdgeNodes& mid,
                     std::vector<std::pair<std::string, int>>& new_nodes, int* m) {
  for (int k = 0; k < 3; ++k) {
    m[k] = mid(face.nodes[k], face.nodes[(k + 1) % 3]);
    new_nodes.emplace_back(name, m[k]);
  }
}

Mesh split_tetrahedra_once(const Mesh& coarse, const SnapToBoundary& snap, NodeParents* parents) {
  Mesh fine;
  fine.dim = 3;
  fine.order = 1;
  fine.nodes = coarse.nodes;
  const int n_elements = coarse.n_elements();
  fine.nodes.reserve(coarse.nodes.size() + expected_edges(n_elements));
  fine.elements.reserve(32 * static_cast<std::size_t>(n_elements));
  EdgeNodes mid(fine, expected_edges(n_elements), parents);
  int n[10];
  for (int e = 0; e < n_elements; ++e) {
    const int* v = coarse.element(e);
    for (int k = 0; k < 4; ++k) n[k] = v[k];
    for (int k = 0; k < 6; ++k) n[4 + k] = mid(v[kEdges[k][0]], v[kEdges[k][1]]);
    for (const auto& child : kCorners)
      for (int k : child) fine.elements.push_back(n[k]);
    // The shortest diagonal keeps the children's shapes closest to the parent's (the new nodes
    // are still the chords' midpoints here: snapping comes after).
    int best = 0;
    double shortest = 0;
    for (int d = 0; d < 3; ++d) {
      const double length = (fine.nodes[n[kDiagonals[d][0]]] - fine.nodes[n[kDiagonals[d][1]]]).squaredNorm();
      if (d == 0 || length < shortest) best = d, shortest = length;
    }
    for (const auto& child : kOctahedron[best])
      for (int k : child) fine.elements.push_back(n[k]);
  }
  std::vector<std::pair<std::string, int>> new_nodes;
  for (const auto& [name, faces] : coarse.boundaries) {
    auto& split = fine.boundaries[name];
    split.reserve(4 * faces.size());
    for (const BoundaryFace& face : faces) {
      int m[3];  // mid-edges 01, 12, 20
      list_face_nodes(name, face, mid, new_nodes, m);
      const int a = face.nodes[0], b = face.nodes[1], c = face.nodes[2];
      // The corner triangles, then the middle one: each keeps the parent's orientation.
      for (const std::array<int, 3>& nodes :
           {std::array<int, 3>{a, m[0], m[2]}, std::array<int, 3>{m[0], b, m[1]}, std::array<int, 3>{m[2], m[1], c},
            std::array<int, 3>{m[0], m[1], m[2]}}) {
        BoundaryFace child;
        child.n_nodes = 3;
        for (int k = 0; k < 3; ++k) child.nodes[k] = nodes[k];
        split.push_back(child);
      }
    }
  }
  snap_boundary_nodes(fine, new_nodes, snap);
  for (const auto& [name, elements] : coarse.regions) {
    auto& children = fine.regions[name];
    children.reserve(8 * elements.size());
    for (int e : elements)
      for (int k = 0; k < 8; ++k) children.push_back(8 * e + k);
  }
  fine.points = coarse.points;
  return fine;
}

}  // namespace

Mesh refine_tetrahedra(const Mesh& mesh, int times, int order, const SnapToBoundary& snap, NodeParents* parents) {
  if (mesh.dim != 3 || mesh.order != 1)
    throw std::runtime_error("refine_tetrahedra: needs a mesh of 4-node tetrahedra");
  Mesh refined = mesh;
  for (int k = 0; k < times; ++k) refined = split_tetrahedra_once(refined, snap, parents);
  if (order == 2) {
    std::vector<std::array<int, 2>> edges;
    for (const auto& edge : kEdges) edges.push_back({edge[0], edge[1]});
    refined = with_mid_edge_nodes(refined, edges, expected_edges(refined.n_elements()), snap, parents);
  }
  orient(refined);  // checks every element too: a snapped node must not invert one
  return refined;
}

}  // namespace contactqp::detail
