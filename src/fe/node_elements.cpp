// elements_at_nodes() and neighbours_of() (node_elements.hpp).
#include "node_elements.hpp"

#include <algorithm>

namespace contactqp::detail {

ElementsAtNodes elements_at_nodes(const Mesh& mesh, const std::vector<char>& keep) {
  const int npe = mesh.nodes_per_element(), n_nodes = mesh.n_nodes();
  const auto kept = [&](int e) { return keep.empty() || keep[e]; };
  ElementsAtNodes at;
  at.first.assign(n_nodes + 1, 0);
  for (int e = 0; e < mesh.n_elements(); ++e)
    if (kept(e))
      for (int k = 0; k < npe; ++k) ++at.first[mesh.element(e)[k] + 1];
  for (int v = 0; v < n_nodes; ++v) at.first[v + 1] += at.first[v];
  at.element.resize(at.first.back());
  std::vector<long> next(at.first.begin(), at.first.end() - 1);
  for (int e = 0; e < mesh.n_elements(); ++e)
    if (kept(e))
      for (int k = 0; k < npe; ++k) at.element[next[mesh.element(e)[k]]++] = e;
  return at;
}

void neighbours_of(const Mesh& mesh, const ElementsAtNodes& at, int node, std::vector<int>& out) {
  const int npe = mesh.nodes_per_element();
  out.clear();
  for (long k = at.first[node]; k < at.first[node + 1]; ++k) {
    const int* v = mesh.element(at.element[k]);
    out.insert(out.end(), v, v + npe);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace contactqp::detail
