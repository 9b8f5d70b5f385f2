// p1_coarse_space() (coarse_space.hpp): the P2 → P1 nodal interpolation of a quadratic mesh.
#include "coarse_space.hpp"

#include <array>
#include <vector>

#include "rigid_body_modes.hpp"

namespace contactqp::detail {
namespace {

// The vertices each mid-edge node of an element lies between, in the element's node order
// (mesh.hpp): 6-node triangles 01, 12, 20; 10-node tetrahedra 01, 12, 20, 03, 13, 23.
const std::vector<std::array<int, 2>>& edges_of(ElementType type) {
  static const std::vector<std::array<int, 2>> triangle{{{0, 1}}, {{1, 2}}, {{2, 0}}};
  static const std::vector<std::array<int, 2>> tetrahedron{{{0, 1}}, {{1, 2}}, {{2, 0}}, {{0, 3}}, {{1, 3}}, {{2, 3}}};
  return type == ElementType::Tet10 ? tetrahedron : triangle;
}

}  // namespace

CoarseSpace p1_coarse_space(const Model& model) {
  CoarseSpace space;
  const Mesh& mesh = model.mesh;
  if (mesh.order != 2) return space;
  const int dim = model.dim, n_nodes = mesh.n_nodes(), n_vertices_per_element = dim + 1;
  const auto& edges = edges_of(mesh.type());
  // Each node: a vertex (its number among the vertices) or a mid-edge node (its edge's ends).
  std::vector<int> vertex(n_nodes, -1);
  std::vector<std::array<int, 2>> ends(n_nodes, {{-1, -1}});
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* element = mesh.element(e);
    for (int a = 0; a < n_vertices_per_element; ++a) vertex[element[a]] = 0;
    for (std::size_t k = 0; k < edges.size(); ++k)
      ends[element[n_vertices_per_element + k]] = {{element[edges[k][0]], element[edges[k][1]]}};
  }
  int n_vertices = 0;
  for (int node = 0; node < n_nodes; ++node)
    if (vertex[node] == 0) vertex[node] = n_vertices++;
  std::vector<Eigen::MatrixXd> frame(n_nodes);  // only where needed: every node's DOF frame
  for (int node = 0; node < n_nodes; ++node) frame[node] = dof_frame(model, node);

  // Rows of the free DOFs: a vertex's own value, or half of each end's, rotated between
  // frames: u'_m = F_mᵀ ½(F_a u'_a + F_b u'_b).
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<char> reached(static_cast<std::size_t>(dim) * n_vertices, 0);
  auto add_block = [&](int node, int from, double weight) {
    // A vertex's own DOFs: exactly the identity (no round-off of FᵀF), so that its row of P
    // is a single 1 and the bound form can give its columns the vertex's own variables.
    const Eigen::MatrixXd block = node == from ? Eigen::MatrixXd::Identity(dim, dim).eval()
                                               : (weight * frame[node].transpose() * frame[from]).eval();
    for (int r = 0; r < dim; ++r) {
      const int row = model.free_index[dim * node + r];
      if (row < 0) continue;
      for (int c = 0; c < dim; ++c)
        if (block(r, c) != 0) {
          entries.emplace_back(row, dim * vertex[from] + c, block(r, c));
          reached[dim * vertex[from] + c] = 1;
        }
    }
  };
  for (int node = 0; node < n_nodes; ++node) {
    if (vertex[node] >= 0) {
      add_block(node, node, 1.0);
    } else if (ends[node][0] >= 0) {
      add_block(node, ends[node][0], 0.5);
      add_block(node, ends[node][1], 0.5);
    }
  }
  // Columns in use, numbered in order; the others left out.
  std::vector<int> column(reached.size(), -1);
  int n_columns = 0;
  for (std::size_t c = 0; c < reached.size(); ++c)
    if (reached[c]) column[c] = n_columns++;
  for (Eigen::Triplet<double>& t : entries) t = Eigen::Triplet<double>(t.row(), column[t.col()], t.value());
  space.interpolation.resize(model.n_free, n_columns);
  space.interpolation.setFromTriplets(entries.begin(), entries.end());
  space.block_size = dim;

  const RigidBodyMotions motions(model);
  space.near_null_space.setZero(n_columns, motions.n_modes());
  space.column_dof.assign(n_columns, -1);
  space.column_vertex.assign(n_columns, -1);
  for (int node = 0; node < n_nodes; ++node) {
    if (vertex[node] < 0) continue;
    const Eigen::MatrixXd local = motions.at(node);
    for (int c = 0; c < dim; ++c) {
      const int col = column[dim * vertex[node] + c];
      if (col < 0) continue;
      space.near_null_space.row(col) = local.row(c);
      space.column_dof[col] = model.free_index[dim * node + c];
      space.column_vertex[col] = vertex[node];
    }
  }
  return space;
}

}  // namespace contactqp::detail
