// number_coarse_entities() and CoarseLattice (coarse_lattice.hpp).
#include "coarse_lattice.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <unordered_map>

namespace contactqp::detail {
namespace {

constexpr std::array<int, 2> kEdges[6] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};

// A point of a coarse simplex's lattice: the vertices (global numbers, ascending) with nonzero
// weight, and the weights (summing to the lattice's denominator).
struct LatticePoint {
  int n = 0;
  std::array<int, 4> vertex{};
  std::array<int, 4> weight{};
};

// The mean of two points of one simplex: the weights of the union of their vertices, halved
// (even at every level but the last: the denominator has the factor 2 of each split).
LatticePoint midpoint(const LatticePoint& a, const LatticePoint& b) {
  LatticePoint m;
  int i = 0, j = 0;
  while (i < a.n || j < b.n) {
    int vertex, weight;
    if (j >= b.n || (i < a.n && a.vertex[i] < b.vertex[j])) {
      vertex = a.vertex[i];
      weight = a.weight[i++];
    } else if (i >= a.n || b.vertex[j] < a.vertex[i]) {
      vertex = b.vertex[j];
      weight = b.weight[j++];
    } else {
      vertex = a.vertex[i];
      weight = a.weight[i++] + b.weight[j++];
    }
    if (m.n == 4) throw std::logic_error("coarse lattice: a refined edge leaves its coarse simplex");
    m.vertex[m.n] = vertex;
    m.weight[m.n++] = weight;
  }
  for (int k = 0; k < m.n; ++k) {
    if (m.weight[k] % 2) throw std::logic_error("coarse lattice: more splits than the denominator allows");
    m.weight[k] /= 2;
  }
  return m;
}

std::uint64_t pair_key(int a, int b) { return std::uint64_t(std::uint32_t(a)) << 32 | std::uint32_t(b); }

}  // namespace

int edges_per_simplex(int dim) { return dim == 2 ? 3 : 6; }

std::array<int, 4> simplex_key(std::array<int, 4> vertices, int n) {
  for (int k = n; k < 4; ++k) vertices[k] = -1;
  // Insertion sort of the first n (a library sort over a run-time prefix of a small array trips
  // GCC's -Warray-bounds).
  for (int i = 1; i < n; ++i)
    for (int j = i; j > 0 && vertices[j - 1] > vertices[j]; --j) std::swap(vertices[j - 1], vertices[j]);
  return vertices;
}

const std::array<int, 2>& simplex_edge(int k) { return kEdges[k]; }

std::array<int, 3> simplex_face(int k) {
  std::array<int, 3> face{};
  int n = 0;
  for (int v = 0; v < 4; ++v)
    if (v != k) face[n++] = v;
  return face;
}

CoarseEntities number_coarse_entities(const Mesh& coarse) {
  CoarseEntities out;
  out.dim = coarse.dim;
  const int n_edges = edges_per_simplex(coarse.dim);
  const int n_elements = coarse.n_elements();
  out.n_vertices = coarse.n_nodes();  // names of vertices are node numbers: mid-edge nodes leave gaps
  out.n_cells = n_elements;
  std::unordered_map<std::uint64_t, int> edges;
  edges.reserve(static_cast<std::size_t>(n_elements) * 2);
  out.element_edges.resize(static_cast<std::size_t>(n_elements) * n_edges);
  for (int e = 0; e < n_elements; ++e) {
    const int* v = coarse.element(e);
    for (int k = 0; k < n_edges; ++k) {
      const int a = v[kEdges[k][0]], b = v[kEdges[k][1]];
      const auto [it, inserted] =
          edges.emplace(pair_key(std::min(a, b), std::max(a, b)), static_cast<int>(edges.size()));
      out.element_edges[static_cast<std::size_t>(e) * n_edges + k] = it->second;
    }
  }
  out.n_edges = static_cast<long long>(edges.size());
  if (coarse.dim == 3) {
    std::map<std::array<int, 4>, int> faces;
    out.element_faces.resize(static_cast<std::size_t>(n_elements) * 4);
    for (int e = 0; e < n_elements; ++e) {
      const int* v = coarse.element(e);
      for (int k = 0; k < 4; ++k) {
        const std::array<int, 3> local = simplex_face(k);
        const std::array<int, 4> face = simplex_key({v[local[0]], v[local[1]], v[local[2]], -1}, 3);
        const auto [it, inserted] = faces.emplace(face, static_cast<int>(faces.size()));
        out.element_faces[static_cast<std::size_t>(e) * 4 + k] = it->second;
      }
    }
    out.n_faces = static_cast<long long>(faces.size());
  }
  return out;
}

CoarseLattice::CoarseLattice(int dim, int refinements, int order, const CoarseEntities& totals)
    : dim_(dim), refinements_(refinements) {
  denominator_ = refinements > 0 ? (1 << refinements) * (order == 2 ? 2 : 1) : 1;
  const long long D = denominator_;
  n_vertices_ = totals.n_vertices;
  n_edges_ = totals.n_edges;
  n_faces_ = totals.n_faces;
  const long long on_edge = std::max(0LL, D - 1), on_triangle = std::max(0LL, (D - 1) * (D - 2) / 2),
                  in_tetrahedron = std::max(0LL, (D - 1) * (D - 2) * (D - 3) / 6);
  edge_offset_ = n_vertices_;
  face_offset_ = edge_offset_ + n_edges_ * on_edge;
  cell_offset_ = face_offset_ + (dim == 3 ? n_faces_ * on_triangle : 0);
  size_ = refinements > 0 ? cell_offset_ + totals.n_cells * (dim == 3 ? in_tetrahedron : on_triangle) : n_vertices_;
}

std::vector<long long> CoarseLattice::names(const Mesh& part, const std::vector<int>& part_vertex,
                                            const std::vector<int>& part_cell, const std::vector<int>& part_edges,
                                            const std::vector<int>& part_faces, const NodeParents& parents) const {
  if (refinements_ == 0) return std::vector<long long>(part_vertex.begin(), part_vertex.end());
  const long long D = denominator_;
  const int n_coarse = static_cast<int>(part_vertex.size());
  std::vector<LatticePoint> point(n_coarse + parents.size());
  for (int v = 0; v < n_coarse; ++v) {
    point[v].n = 1;
    point[v].vertex[0] = part_vertex[v];
    point[v].weight[0] = denominator_;
  }
  for (std::size_t k = 0; k < parents.size(); ++k)
    point[n_coarse + k] = midpoint(point[parents[k][0]], point[parents[k][1]]);

  // The entities of the part's elements by their vertices' global numbers (ascending).
  const int nv = dim_ + 1, n_edges = edges_per_simplex(dim_), npe = part.nodes_per_element();
  const int n_elements = static_cast<int>(part_cell.size());
  std::unordered_map<std::uint64_t, int> edge_of;
  std::map<std::array<int, 4>, int> simplex_of;  // faces (3D, last entry −1) and cells
  for (int e = 0; e < n_elements; ++e) {
    const int* v = part.elements.data() + static_cast<std::size_t>(e) * npe;
    for (int k = 0; k < n_edges; ++k) {
      const int a = part_vertex[v[kEdges[k][0]]], b = part_vertex[v[kEdges[k][1]]];
      edge_of.emplace(pair_key(std::min(a, b), std::max(a, b)), part_edges[static_cast<std::size_t>(e) * n_edges + k]);
    }
    std::array<int, 4> cell = {-1, -1, -1, -1};
    for (int k = 0; k < nv; ++k) cell[k] = part_vertex[v[k]];
    simplex_of.emplace(simplex_key(cell, nv), part_cell[e]);
    if (dim_ == 3)
      for (int k = 0; k < 4; ++k) {
        const std::array<int, 3> local = simplex_face(k);
        const std::array<int, 4> face =
            simplex_key({part_vertex[v[local[0]]], part_vertex[v[local[1]]], part_vertex[v[local[2]]], -1}, 3);
        simplex_of.emplace(face, part_faces[static_cast<std::size_t>(e) * 4 + k]);
      }
  }
  // Only the nodes of the part's refined elements have names; the refinement made no others.
  std::vector<long long> out(point.size(), -1);
  for (std::size_t node = 0; node < point.size(); ++node) {
    const LatticePoint& p = point[node];
    const auto w = [&p](int k) { return static_cast<long long>(p.weight[k]) - 1; };  // interior: weights ≥ 1
    if (p.n == 1) {
      out[node] = p.vertex[0];
    } else if (p.n == 2) {
      out[node] = edge_offset_ + edge_of.at(pair_key(p.vertex[0], p.vertex[1])) * (D - 1) + w(1);
    } else if (p.n == 3) {
      const long long s = w(1) + w(2), index = s * (s + 1) / 2 + w(2);
      const long long entity = simplex_of.at({p.vertex[0], p.vertex[1], p.vertex[2], -1});
      out[node] = (dim_ == 3 ? face_offset_ : cell_offset_) + entity * ((D - 1) * (D - 2) / 2) + index;
    } else {
      const long long s = w(1) + w(2) + w(3), t = w(2) + w(3);
      const long long index = s * (s + 1) * (s + 2) / 6 + t * (t + 1) / 2 + w(3);
      const long long entity = simplex_of.at({p.vertex[0], p.vertex[1], p.vertex[2], p.vertex[3]});
      out[node] = cell_offset_ + entity * ((D - 1) * (D - 2) * (D - 3) / 6) + index;
    }
  }
  return out;
}

}  // namespace contactqp::detail
