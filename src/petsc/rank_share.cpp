// distributed_rows(), check_same_model_on_every_rank() and owned_elements() (rank_share.hpp).
#include "rank_share.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "contactqp/mesh.hpp"
#include "fe/node_elements.hpp"
#include "mpi.hpp"

namespace contactqp::detail {
namespace {

// The rank whose block of rows holds `row`: PETSc's split of n rows into `ranks` contiguous
// blocks, the first n % ranks of them one row longer (PetscSplitOwnership).
int owner_of_row(int row, int n, int ranks) {
  const int q = n / ranks, r = n % ranks;
  return row < r * (q + 1) ? row / (q + 1) : r + (row - r * (q + 1)) / q;
}

// The mesh's nodes and, for each, the nodes it shares an element with (itself included).
void node_graph(const Mesh& mesh, std::vector<long>& offsets, std::vector<int>& neighbours) {
  const ElementsAtNodes at = elements_at_nodes(mesh);
  offsets.assign(1, 0);
  neighbours.clear();
  std::vector<int> around;
  for (int v = 0; v < mesh.n_nodes(); ++v) {
    neighbours_of(mesh, at, v, around);
    neighbours.insert(neighbours.end(), around.begin(), around.end());
    offsets.push_back(static_cast<long>(neighbours.size()));
  }
}

}  // namespace

std::vector<int> distributed_rows(const Model& model, int ranks) {
  std::vector<long> offsets;
  std::vector<int> neighbours;
  node_graph(model.mesh, offsets, neighbours);
  const std::vector<int> part = partition_graph(offsets, neighbours, ranks);
  if (part.empty()) return {};
  const int dim = model.dim;
  // Each free column's part: its first DOF's node's. A rigid surface's DOFs (model.hpp's
  // RigidSurface) share one column, which gets one row.
  std::vector<int> part_of_column(model.n_free, -1);
  for (std::size_t dof = 0; dof < model.free_index.size(); ++dof) {
    const int column = model.free_index[dof];
    if (column >= 0 && part_of_column[column] < 0) part_of_column[column] = part[dof / dim];
  }
  // A turning surface's angle has no DOF of its own: its surface's first node's part.
  for (const RigidRotation& turn : model.rigid_rotations) part_of_column[turn.column] = part[turn.nodes.front()];
  // Counting sort of the free columns by their part, stable within a part.
  std::vector<int> start(ranks + 1, 0);
  for (int p : part_of_column) ++start[p + 1];
  for (int p = 0; p < ranks; ++p) start[p + 1] += start[p];
  std::vector<int> row(model.n_free);
  for (int column = 0; column < model.n_free; ++column) row[column] = start[part_of_column[column]]++;
  return row;
}

void check_same_model_on_every_rank(const Model& model) {
  const int ranks = mpi_size();
  if (ranks <= 1) return;
  const Mesh& mesh = model.mesh;
  double checksum = 0;
  for (int v = 0; v < mesh.n_nodes(); ++v)
    for (int c = 0; c < mesh.dim; ++c) checksum += (1 + (v + c) % 7) * mesh.nodes[v][c];
  const double mine[4] = {static_cast<double>(mesh.n_nodes()), static_cast<double>(mesh.n_elements()),
                          static_cast<double>(model.n_free), checksum};
  // Every rank's values, each in its own slots (the others add zeros: the sum is exact).
  std::vector<double> all(4 * static_cast<std::size_t>(ranks), 0.0);
  std::copy(mine, mine + 4, all.begin() + 4 * mpi_rank());
  sum_over_ranks(all.data(), static_cast<long>(all.size()));
  if (!std::equal(all.begin(), all.end() - 4, all.begin() + 4))
    throw std::runtime_error(
        "the MPI ranks built different models of the scene (nodes, elements, DOFs or coordinates differ; this rank: " +
        std::to_string(mesh.n_nodes()) + " nodes, " + std::to_string(mesh.n_elements()) + " elements, " +
        std::to_string(model.n_free) + " DOFs): each rank meshes the scene itself, which must give one mesh");
}

std::vector<char> owned_elements(const Model& model, const RankShare& share, const std::vector<int>& distributed_row) {
  const Mesh& mesh = model.mesh;
  const int npe = mesh.nodes_per_element(), dim = mesh.dim;
  std::vector<char> owned(mesh.n_elements(), 1);
  if (share.ranks <= 1) return owned;
  for (int e = 0; e < mesh.n_elements(); ++e) {
    // The row of the element's first free DOF, in node order: an element on the boundary
    // between two ranks' rows goes to either side alike (the lowest row would give them all to
    // the lower rank).
    int first = -1;
    const int* v = mesh.element(e);
    for (int i = 0; i < npe && first < 0; ++i)
      for (int c = 0; c < dim && first < 0; ++c) {
        const int free = model.free_index[dim * v[i] + c];
        if (free >= 0) first = distributed_row.empty() ? free : distributed_row[free];
      }
    owned[e] = first >= 0 && owner_of_row(first, model.n_free, share.ranks) == share.rank;
  }
  return owned;
}

}  // namespace contactqp::detail
