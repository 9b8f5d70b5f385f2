#include "refine.hpp"

#include <stdexcept>

#include "edge_nodes.hpp"

namespace contactqp::detail {
namespace {

Mesh split_triangles_once(const Mesh& coarse, const SnapToBoundary& snap, NodeParents* parents) {
  Mesh fine;
  fine.dim = 2;
  fine.order = 1;
  fine.nodes = coarse.nodes;
  const int n_elements = coarse.n_elements();
  fine.nodes.reserve(coarse.nodes.size() + 3 * static_cast<std::size_t>(n_elements) / 2 + 64);
  fine.elements.reserve(12 * static_cast<std::size_t>(n_elements));
  EdgeNodes mid(fine, 3 * static_cast<std::size_t>(n_elements) / 2 + 64, parents);
  for (int e = 0; e < n_elements; ++e) {
    const int* v = coarse.element(e);
    const int m01 = mid(v[0], v[1]), m12 = mid(v[1], v[2]), m20 = mid(v[2], v[0]);
    // The corner triangles, then the middle one: each keeps the parent's orientation.
    for (int node : {v[0], m01, m20, m01, v[1], m12, m20, m12, v[2], m01, m12, m20}) fine.elements.push_back(node);
  }
  std::vector<std::pair<std::string, int>> new_nodes;
  for (const auto& [name, faces] : coarse.boundaries) {
    auto& split = fine.boundaries[name];
    split.reserve(2 * faces.size());
    for (const BoundaryFace& face : faces) {
      const int m = mid(face.nodes[0], face.nodes[1]);
      new_nodes.emplace_back(name, m);
      BoundaryFace first, second;
      first.n_nodes = second.n_nodes = 2;
      first.nodes[0] = face.nodes[0];
      first.nodes[1] = m;
      second.nodes[0] = m;
      second.nodes[1] = face.nodes[1];
      split.push_back(first);
      split.push_back(second);
    }
  }
  snap_boundary_nodes(fine, new_nodes, snap);
  for (const auto& [name, elements] : coarse.regions) {
    auto& children = fine.regions[name];
    for (int e : elements)
      for (int k = 0; k < 4; ++k) children.push_back(4 * e + k);
  }
  fine.points = coarse.points;
  return fine;
}

}  // namespace

Mesh refine_triangles(const Mesh& mesh, int times, int order, const SnapToBoundary& snap, NodeParents* parents) {
  if (mesh.dim != 2 || mesh.order != 1) throw std::runtime_error("refine_triangles: needs a mesh of 3-node triangles");
  Mesh refined = mesh;
  for (int k = 0; k < times; ++k) refined = split_triangles_once(refined, snap, parents);
  // 6-node triangles: vertices, then the mid-sides 01, 12, 20.
  if (order == 2)
    refined = with_mid_edge_nodes(refined, {{0, 1}, {1, 2}, {2, 0}},
                                  3 * static_cast<std::size_t>(refined.n_elements()) / 2 + 64, snap, parents);
  orient(refined);  // checks every element too: a snapped node must not invert one
  return refined;
}

long long refined_children(int dim, int refinements) { return 1LL << (dim * refinements); }

Mesh refine_coarse(const CoarseMesh& coarse, const Mesh& part, NodeParents* parents) {
  if (coarse.refinements == 0) return part;
  Mesh refined = part.dim == 2 ? refine_triangles(part, coarse.refinements, coarse.order, coarse.snap, parents)
                               : refine_tetrahedra(part, coarse.refinements, coarse.order, coarse.snap, parents);
  for (Eigen::Vector3d& x : refined.nodes) x *= coarse.scale;
  return refined;
}

}  // namespace contactqp::detail
