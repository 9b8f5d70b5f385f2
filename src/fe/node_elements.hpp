// The elements at each node of a mesh, and each node's neighbours (the nodes it shares an
// element with): K's pattern (stiffness_matrix.cpp) and the graph the ranks' partition splits
// (src/petsc/rank_share.cpp) both come from them.
#pragma once

#include <vector>

#include "contactqp/mesh.hpp"

namespace contactqp::detail {

// CSR: the elements at node v are element[first[v]] .. element[first[v + 1] − 1], in element
// order. Only the elements with keep[e] != 0, or all of them when keep is empty.
struct ElementsAtNodes {
  std::vector<long> first;
  std::vector<int> element;
};
ElementsAtNodes elements_at_nodes(const Mesh& mesh, const std::vector<char>& keep = {});

// The nodes that share one of those elements with `node` (itself included), ascending, in `out`.
void neighbours_of(const Mesh& mesh, const ElementsAtNodes& at, int node, std::vector<int>& out);

}  // namespace contactqp::detail
