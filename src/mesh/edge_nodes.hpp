// The new node at the middle of each edge of a mesh being refined, made once and shared by
// the elements and boundary faces that hold the edge (refine.cpp, refine_tetrahedra.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "contactqp/mesh.hpp"
#include "refine.hpp"

namespace contactqp::detail {

// Edges are keyed by their two end nodes; a new node is appended to mesh.nodes at the chord's
// midpoint the first time its edge is asked for.
class EdgeNodes {
 public:
  // `parents`, when given, receives the two end nodes of each new node's edge (refine.hpp).
  EdgeNodes(Mesh& mesh, std::size_t expected, NodeParents* parents = nullptr) : mesh_(mesh), parents_(parents) {
    index_.reserve(expected);
  }

  int operator()(int a, int b) {
    const std::uint64_t key =
        a < b ? (std::uint64_t(a) << 32 | std::uint32_t(b)) : (std::uint64_t(b) << 32 | std::uint32_t(a));
    auto [it, inserted] = index_.emplace(key, mesh_.n_nodes());
    if (inserted) {
      mesh_.nodes.push_back(0.5 * (mesh_.nodes[a] + mesh_.nodes[b]));
      if (parents_) parents_->push_back({a, b});
    }
    return it->second;
  }

 private:
  Mesh& mesh_;
  NodeParents* parents_;
  std::unordered_map<std::uint64_t, int> index_;
};

// Snaps each new node of a named boundary's edges onto that boundary (a node on two boundaries,
// such as a rim, is listed under each and ends on both: the snaps of the shapes keep each other).
inline void snap_boundary_nodes(Mesh& mesh, const std::vector<std::pair<std::string, int>>& new_nodes,
                                const SnapToBoundary& snap) {
  for (const auto& [name, node] : new_nodes) mesh.nodes[node] = snap(name, mesh.nodes[node]);
}

// `linear` (order 1) as the order-2 mesh of the same elements: each element's vertices, then a
// node at the middle of each of `edges` (pairs of local vertices, in the element type's order);
// each boundary face's vertices, then its edges' middles (a segment's 01; a triangle's 01, 12,
// 20), snapped onto their boundary. Regions and points as they were. `expected_edges` sizes
// the edge table.
Mesh with_mid_edge_nodes(const Mesh& linear, const std::vector<std::array<int, 2>>& edges, std::size_t expected_edges,
                         const SnapToBoundary& snap, NodeParents* parents = nullptr);

}  // namespace contactqp::detail
