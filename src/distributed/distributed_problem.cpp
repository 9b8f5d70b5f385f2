// assemble_distributed_bound_qp() (distributed_problem.hpp).
#include "distributed_problem.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

#include "coarse_lattice.hpp"
#include "contact/contact.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/phases.hpp"
#include "fe/node_elements.hpp"
#include "fe/stiffness_matrix.hpp"
#include "model/model_parts.hpp"
#include "model/rigid_body_modes.hpp"
#include "petsc/petsc_runtime.hpp"
#include "qp/bound_transform.hpp"
#include "world.hpp"

namespace contactqp::detail {
namespace {

// The transform of every candidate node this rank holds; the candidates of one node are
// consecutive (select_candidates() goes node by node). A node's rows that are linearly
// dependent are bad input, reported by the rank that owns the node.
void make_transforms(const DistributedModel& dm, DistributedBoundQp& qp) {
  const Model& model = dm.local;
  const auto& candidates = model.candidates;
  qp.transform_of_node.assign(model.mesh.n_nodes(), -1);
  for (std::size_t first = 0; first < candidates.size();) {
    std::size_t end = first;
    while (end < candidates.size() && candidates[end].node == candidates[first].node) ++end;
    NodeTransform t;
    t.node = candidates[first].node;
    t.first_candidate = static_cast<int>(first);
    t.n_rows = static_cast<int>(end - first);
    std::vector<ContactRowEntries> rows;
    for (std::size_t i = first; i < end; ++i) {
      rows.push_back(contact_row(model, candidates[i]));
      for (const auto& [column, value] : rows.back().coefficients) t.columns.push_back(column);
    }
    std::sort(t.columns.begin(), t.columns.end());
    t.columns.erase(std::unique(t.columns.begin(), t.columns.end()), t.columns.end());
    Eigen::MatrixXd block = Eigen::MatrixXd::Zero(t.n_rows, t.columns.size());
    for (int a = 0; a < t.n_rows; ++a)
      for (const auto& [column, value] : rows[a].coefficients)
        block(a, std::lower_bound(t.columns.begin(), t.columns.end(), column) - t.columns.begin()) = value;
    if (!bound_transform(block, t.T, t.Q)) {
      if (t.node >= dm.n_owned) {  // its owner says so
        first = end;
        continue;
      }
      throw std::runtime_error("the contact rows of node group starting at row " +
                               std::to_string(dm.first_candidate + static_cast<PetscInt>(first)) + " (" +
                               std::to_string(t.n_rows) + " rows on " + std::to_string(t.columns.size()) +
                               " DOFs) are linearly dependent; the petsc backend needs independent rows at each node");
    }
    qp.transform_of_node[t.node] = static_cast<int>(qp.transforms.size());
    qp.transforms.push_back(std::move(t));
    first = end;
  }
}

// Nonzeros of each own row of A in PETSc's diagonal block (columns of this rank's rows) and
// off it: a node's rows couple to every free DOF of the nodes it shares an element with. A node
// on the border between parts has elements on several ranks: the others send the owner their
// neighbours of it (global node, its free DOFs), which it adds to its own.
void count_nonzeros(const DistributedModel& dm, std::vector<PetscInt>& diagonal, std::vector<PetscInt>& off) {
  const Model& model = dm.local;
  const Mesh& mesh = model.mesh;
  const int n = mesh.n_nodes(), dim = model.dim, ranks = world_size();
  std::vector<int> free_of_node(n, 0);
  for (int node = 0; node < n; ++node)
    for (int c = 0; c < dim; ++c) free_of_node[node] += model.free_index[dim * node + c] >= 0;
  std::vector<double> holders(n, 1.0);
  dm.shared.sum(holders.data(), 1);
  std::vector<int> first_node(ranks + 1, 0);
  const int mine = dm.n_owned;
  MPI_Allgather(&mine, 1, MPI_INT, first_node.data() + 1, 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 0; r < ranks; ++r) first_node[r + 1] += first_node[r];
  const int rank = world_rank();
  const auto owner = [&](int global) {
    return static_cast<int>(std::upper_bound(first_node.begin(), first_node.end(), global) - first_node.begin()) - 1;
  };

  const ElementsAtNodes at = elements_at_nodes(mesh);
  std::vector<int> around;
  // Shared nodes: (node, neighbour, its free DOFs) triples, to the node's owner.
  std::vector<std::vector<int>> outgoing(ranks);
  // Own shared nodes: their neighbours' global numbers and free DOFs, merged below.
  std::unordered_map<int, std::vector<std::pair<int, int>>> merged;
  std::vector<long long> d_node(mine, 0), o_node(mine, 0);
  for (int node = 0; node < n; ++node) {
    if (free_of_node[node] == 0 && node >= mine) continue;
    neighbours_of(mesh, at, node, around);
    const bool shared = holders[node] > 1.5;
    if (node >= mine) {
      std::vector<int>& to = outgoing[owner(dm.global_node[node])];
      for (int j : around) to.insert(to.end(), {dm.global_node[node], dm.global_node[j], free_of_node[j]});
      continue;
    }
    if (shared) {
      auto& list = merged[dm.global_node[node]];
      for (int j : around) list.emplace_back(dm.global_node[j], free_of_node[j]);
      continue;
    }
    for (int j : around) (j < mine ? d_node : o_node)[node] += free_of_node[j];
  }
  std::vector<int> send_counts(ranks), receive_counts(ranks), send_offsets(ranks, 0), receive_offsets(ranks, 0);
  std::vector<int> sending;
  for (int r = 0; r < ranks; ++r) {
    send_counts[r] = static_cast<int>(outgoing[r].size());
    send_offsets[r] = static_cast<int>(sending.size());
    sending.insert(sending.end(), outgoing[r].begin(), outgoing[r].end());
  }
  outgoing = {};
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 1; r < ranks; ++r) receive_offsets[r] = receive_offsets[r - 1] + receive_counts[r - 1];
  std::vector<int> received(receive_offsets.back() + receive_counts.back());
  MPI_Alltoallv(sending.data(), send_counts.data(), send_offsets.data(), MPI_INT, received.data(),
                receive_counts.data(), receive_offsets.data(), MPI_INT, MPI_COMM_WORLD);
  for (std::size_t k = 0; k + 2 < received.size(); k += 3)
    merged[received[k]].emplace_back(received[k + 1], received[k + 2]);
  const int first_global = first_node[rank], end_global = first_node[rank + 1];
  for (auto& [global, list] : merged) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
               list.end());
    const int node = global - first_global;
    for (const auto& [j, free] : list) (j >= first_global && j < end_global ? d_node : o_node)[node] += free;
  }
  // A free DOF's row couples to the free DOFs of the nodes around; a prescribed DOF's row is
  // its diagonal alone.
  diagonal.assign(dm.n_own_rows, 1);
  off.assign(dm.n_own_rows, 0);
  for (int dof = 0; dof < dim * mine; ++dof) {
    const int free = model.free_index[dof];
    if (free < 0) continue;
    diagonal[dm.local_row(free)] = static_cast<PetscInt>(d_node[dof / dim]);
    off[dm.local_row(free)] = static_cast<PetscInt>(o_node[dof / dim]);
  }
}

// The element matrices into A, each in the bound form's variables.
void add_elements(const DistributedModel& dm, const DistributedBoundQp& qp, double& largest, bool& finite) {
  const Model& model = dm.local;
  const Mesh& mesh = model.mesh;
  const std::vector<ElementLaw> laws = element_laws(model);
  const int npe = mesh.nodes_per_element(), dim = mesh.dim;
  const ElementType type = mesh.type();
  std::vector<Eigen::Vector3d> coordinates(npe);
  std::vector<int> position, free;  // the element's free DOFs: their place in K_e, local index
  std::vector<PetscInt> rows;
  std::vector<int> place;
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    for (int i = 0; i < npe; ++i) coordinates[i] = mesh.nodes[v[i]];
    const Eigen::MatrixXd Ke = dof_frame_rotated(
        model, v, npe,
        element_stiffness(type, coordinates.data(), laws[body_of_element(model, e)], model.scene.body.thickness));
    finite = finite && Ke.allFinite();
    largest = std::max(largest, Ke.cwiseAbs().maxCoeff());
    position.clear();
    free.clear();
    for (int i = 0; i < npe; ++i)
      for (int c = 0; c < dim; ++c) {
        const int column = model.free_index[dim * v[i] + c];
        if (column < 0) continue;
        position.push_back(dim * i + c);
        free.push_back(column);
      }
    const int m = static_cast<int>(free.size());
    if (m == 0) continue;
    // The prescribed DOFs' rows of nodes that have rows: K_pp as if they were free, alone on
    // their row and column (the solver's block size dim keeps every node's DOFs together).
    for (int i = 0; i < npe; ++i)
      for (int c = 0; c < dim; ++c) {
        const int dof = dim * v[i] + c;
        if (model.free_index[dof] >= 0 || dm.node_row[v[i]] < 0) continue;
        const PetscInt row = dm.node_row[v[i]] + c;
        check_petsc(MatSetValue(qp.A, row, row, Ke(dim * i + c, dim * i + c), ADD_VALUES), "MatSetValue");
      }
    Eigen::MatrixXd Kf(m, m);
    for (int k = 0; k < m; ++k)
      for (int l = 0; l < m; ++l) Kf(k, l) = Ke(position[k], position[l]);
    // Q_eᵀ K_e Q_e, node by node (Q is block-diagonal over the nodes).
    for (int i = 0; i < npe; ++i) {
      const int t = qp.transform_of_node[v[i]];
      if (t < 0) continue;
      const NodeTransform& transform = qp.transforms[t];
      place.clear();
      for (int column : transform.columns)
        place.push_back(static_cast<int>(std::find(free.begin(), free.end(), column) - free.begin()));
      const int c = static_cast<int>(place.size());
      Eigen::MatrixXd columns(m, c), rows_block(c, m);
      for (int a = 0; a < c; ++a) columns.col(a) = Kf.col(place[a]);
      columns = columns * transform.Q;
      for (int a = 0; a < c; ++a) Kf.col(place[a]) = columns.col(a);
      for (int a = 0; a < c; ++a) rows_block.row(a) = Kf.row(place[a]);
      rows_block = transform.Q.transpose() * rows_block;
      for (int a = 0; a < c; ++a) Kf.row(place[a]) = rows_block.row(a);
    }
    const Eigen::MatrixXd symmetric = 0.5 * (Kf + Kf.transpose());  // exactly symmetric, for CG and MAT_SPD
    rows.resize(m);
    for (int k = 0; k < m; ++k) rows[k] = dm.row_of_free[free[k]];
    check_petsc(MatSetValues(qp.A, m, rows.data(), m, rows.data(), symmetric.data(), ADD_VALUES), "MatSetValues");
  }
}

// The rigid-body motions at the nodes, as rigid_body_modes() scales them: about the centroid of
// the whole mesh, by its extent (two reductions).
struct RigidMotions {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double extent = 1;
  RigidMotions(const DistributedModel& dm) {
    const Mesh& mesh = dm.local.mesh;
    double sums[4] = {0, 0, 0, static_cast<double>(dm.n_owned)};
    for (int node = 0; node < dm.n_owned; ++node)
      for (int c = 0; c < 3; ++c) sums[c] += mesh.nodes[node][c];
    MPI_Allreduce(MPI_IN_PLACE, sums, 4, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    if (sums[3] > 0) centroid = Eigen::Vector3d(sums[0], sums[1], sums[2]) / sums[3];
    double largest = 0;
    for (int node = 0; node < dm.n_owned; ++node) largest = std::max(largest, (mesh.nodes[node] - centroid).norm());
    MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    if (largest > 0) extent = largest;
  }
  // dim × k at a node, its DOF components (dof_frame()).
  Eigen::MatrixXd at(const Model& model, int node) const {
    return dof_frame(model, node).transpose() * rigid_motions_at(model.dim, model.mesh.nodes[node], centroid, extent);
  }
};

// The rigid-body modes on this rank's rows, in v, orthonormalised over all ranks (Cholesky QR,
// twice: one reduction of a k × k Gram matrix each).
void add_near_null_space(const DistributedModel& dm, DistributedBoundQp& qp, const RigidMotions& rigid) {
  const Model& model = dm.local;
  const int dim = model.dim, k = dim == 2 ? 3 : 6;
  // 0 at the prescribed DOFs' rows (the solver's choice, seam-petsc.md).
  Eigen::MatrixXd modes = Eigen::MatrixXd::Zero(dm.n_own_rows, k);
  for (int node = 0; node < dm.n_owned; ++node) {
    const Eigen::MatrixXd local = rigid.at(model, node);
    for (int c = 0; c < dim; ++c) {
      const int free = model.free_index[dim * node + c];
      if (free >= 0) modes.row(dm.local_row(free)) = local.row(c);
    }
    const int t = qp.transform_of_node[node];
    if (t < 0) continue;
    const NodeTransform& transform = qp.transforms[t];  // v_C = T u_C
    Eigen::MatrixXd block(transform.columns.size(), k);
    for (std::size_t a = 0; a < transform.columns.size(); ++a)
      block.row(a) = modes.row(dm.local_row(transform.columns[a]));
    block = transform.T * block;
    for (std::size_t a = 0; a < transform.columns.size(); ++a)
      modes.row(dm.local_row(transform.columns[a])) = block.row(a);
  }
  for (int pass = 0; pass < 2; ++pass) {
    Eigen::MatrixXd gram = modes.transpose() * modes;
    MPI_Allreduce(MPI_IN_PLACE, gram.data(), k * k, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    const Eigen::LLT<Eigen::MatrixXd> cholesky(gram);
    if (cholesky.info() != Eigen::Success) return;  // dependent modes (a tiny model): GAMG goes without
    modes = cholesky.matrixU().solve<Eigen::OnTheRight>(modes);
  }
  for (int j = 0; j < k; ++j) {
    Vec mode = nullptr;
    check_petsc(MatCreateVecs(qp.A, &mode, nullptr), "MatCreateVecs");
    PetscScalar* values = nullptr;
    VecGetArray(mode, &values);
    for (int row = 0; row < dm.n_own_rows; ++row) values[row] = modes(row, j);
    VecRestoreArray(mode, &values);
    qp.near_null_space.push_back(mode);
  }
}

// The P2 → P1 interpolation and its level's rigid modes (distributed_problem.hpp), for a
// multigrid whose first coarse level is the vertices' linear elements.
void add_coarse_space(const DistributedModel& dm, DistributedBoundQp& qp, const RigidMotions& rigid) {
  const Model& model = dm.local;
  const Mesh& mesh = model.mesh;
  if (mesh.order != 2) return;
  const int dim = model.dim, nv = dim + 1, npe = mesh.nodes_per_element(), n = mesh.n_nodes();
  // Each node a vertex, or a mid-edge node between its edge's two ends.
  std::vector<char> vertex(n, 0);
  std::vector<std::array<int, 2>> ends(n, {-1, -1});
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    for (int k = 0; k < nv; ++k) vertex[v[k]] = 1;
    for (int k = nv; k < npe; ++k) ends[v[k]] = {v[simplex_edge(k - nv)[0]], v[simplex_edge(k - nv)[1]]};
  }
  // The vertices' numbers on the coarse level: each rank's own consecutive.
  long long own = 0, total = 0;
  for (int node = 0; node < dm.n_owned; ++node) own += vertex[node];
  const long long first = first_of_mine(own, &total);
  std::vector<int> coarse(n, -1);
  for (int node = 0, next = static_cast<int>(first); node < dm.n_owned; ++node)
    if (vertex[node]) coarse[node] = next++;
  dm.shared.from_owner(coarse.data(), 1);
  qp.vertex_of_node = coarse;

  // A candidate vertex's coarse columns are in its own variables, as its fine rows are (the
  // bound form's T applied to the vertex columns too, bound_form.cpp): u at the vertex = Q w, so
  // that its bound is a bound on one coarse column and the P1 start can solve the contact
  // problem on that level. in_vertex_variables(vertex, false) is the dim × dim block of u in
  // the vertex's coarse variables (Q on its group's components, the identity elsewhere);
  // (vertex, true) the inverse, T, which takes the rigid modes there.
  auto in_vertex_variables = [&](int node, bool inverse) {
    Eigen::MatrixXd block = Eigen::MatrixXd::Identity(dim, dim);
    const int t = qp.transform_of_node[node];
    if (t < 0) return block;
    const NodeTransform& transform = qp.transforms[t];
    std::vector<int> component;
    for (int column : transform.columns)
      for (int c = 0; c < dim; ++c)
        if (model.free_index[dim * node + c] == column) component.push_back(c);
    const Eigen::MatrixXd& group = inverse ? transform.T : transform.Q;
    for (std::size_t a = 0; a < component.size(); ++a)
      for (std::size_t b = 0; b < component.size(); ++b) block(component[a], component[b]) = group(a, b);
    return block;
  };

  Mat& P = qp.coarse_interpolation;
  check_petsc(MatCreate(PETSC_COMM_WORLD, &P), "MatCreate");
  check_petsc(MatSetSizes(P, dm.n_own_rows, static_cast<PetscInt>(dim * own), static_cast<PetscInt>(dm.n_global_rows),
                          static_cast<PetscInt>(dim * total)),
              "MatSetSizes");
  check_petsc(MatSetType(P, MATAIJ), "MatSetType");
  check_petsc(MatSetBlockSizes(P, dim, dim), "MatSetBlockSizes");
  // At most two vertices' dim columns per row (a candidate node's T mixes its components).
  check_petsc(MatSeqAIJSetPreallocation(P, 2 * dim, nullptr), "MatSeqAIJSetPreallocation");
  check_petsc(MatMPIAIJSetPreallocation(P, 2 * dim, nullptr, 2 * dim, nullptr), "MatMPIAIJSetPreallocation");
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  std::vector<PetscInt> rows(dim), columns;
  for (int node = 0; node < dm.n_owned; ++node) {
    if (dm.node_row[node] < 0) continue;
    const std::vector<int> from =
        vertex[node] ? std::vector<int>{node} : std::vector<int>{ends[node][0], ends[node][1]};
    RowMajor block = RowMajor::Zero(dim, dim * from.size());
    columns.clear();
    for (std::size_t a = 0; a < from.size(); ++a) {
      block.middleCols(dim * a, dim) = in_vertex_variables(from[a], false);
      for (int c = 0; c < dim; ++c) columns.push_back(static_cast<PetscInt>(dim) * coarse[from[a]] + c);
    }
    block /= static_cast<double>(from.size());
    for (int c = 0; c < dim; ++c) {
      rows[c] = dm.node_row[node] + c;
      if (model.free_index[dim * node + c] < 0) block.row(c).setZero();  // a prescribed row
    }
    const int t = qp.transform_of_node[node];
    if (t >= 0) {  // P_v = T P_u on the node's group
      const NodeTransform& transform = qp.transforms[t];
      std::vector<int> component;
      for (int column : transform.columns)
        for (int c = 0; c < dim; ++c)
          if (model.free_index[dim * node + c] == column) component.push_back(c);
      RowMajor part(component.size(), block.cols());
      for (std::size_t a = 0; a < component.size(); ++a) part.row(a) = block.row(component[a]);
      part = transform.T * part;
      for (std::size_t a = 0; a < component.size(); ++a) block.row(component[a]) = part.row(a);
    }
    check_petsc(MatSetValues(P, dim, rows.data(), static_cast<PetscInt>(columns.size()), columns.data(), block.data(),
                             INSERT_VALUES),
                "MatSetValues");
  }
  check_petsc(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check_petsc(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");

  // The coarse level's rigid modes: at each own vertex in its DOF components, 0 where prescribed.
  const int k = dim == 2 ? 3 : 6;
  for (int j = 0; j < k; ++j) {
    Vec mode = nullptr;
    check_petsc(MatCreateVecs(P, &mode, nullptr), "MatCreateVecs");
    qp.coarse_near_null_space.push_back(mode);
  }
  std::vector<PetscScalar*> values(k);
  for (int j = 0; j < k; ++j) VecGetArray(qp.coarse_near_null_space[j], &values[j]);
  for (int node = 0; node < dm.n_owned; ++node) {
    if (!vertex[node]) continue;
    Eigen::MatrixXd motion = rigid.at(model, node);
    for (int c = 0; c < dim; ++c)
      if (model.free_index[dim * node + c] < 0) motion.row(c).setZero();
    motion = in_vertex_variables(node, true) * motion;
    for (int c = 0; c < dim; ++c)
      for (int j = 0; j < k; ++j) values[j][dim * (coarse[node] - first) + c] = motion(c, j);
  }
  for (int j = 0; j < k; ++j) VecRestoreArray(qp.coarse_near_null_space[j], &values[j]);

  // Each own bound's coarse column: its variable's at a candidate vertex, −1 at a mid-edge node
  // (the order of qp.bounded, assemble_distributed_bound_qp()).
  for (const NodeTransform& t : qp.transforms) {
    if (t.node >= dm.n_owned) continue;
    for (int a = 0; a < t.n_rows; ++a) {
      PetscInt column = -1;
      for (int c = 0; c < dim && vertex[t.node]; ++c)
        if (model.free_index[dim * t.node + c] == t.columns[a])
          column = static_cast<PetscInt>(dim) * coarse[t.node] + c;
      qp.coarse_bounded.push_back(column);
    }
  }
}

}  // namespace

DistributedBoundQp::DistributedBoundQp(DistributedBoundQp&& other) noexcept { *this = std::move(other); }

DistributedBoundQp& DistributedBoundQp::operator=(DistributedBoundQp&& other) noexcept {
  std::swap(A, other.A);
  std::swap(b, other.b);
  std::swap(f, other.f);
  std::swap(bounded, other.bounded);
  std::swap(upper, other.upper);
  std::swap(near_null_space, other.near_null_space);
  std::swap(block_size, other.block_size);
  std::swap(coarse_interpolation, other.coarse_interpolation);
  std::swap(coarse_near_null_space, other.coarse_near_null_space);
  std::swap(coarse_bounded, other.coarse_bounded);
  std::swap(vertex_of_node, other.vertex_of_node);
  std::swap(transforms, other.transforms);
  std::swap(transform_of_node, other.transform_of_node);
  return *this;
}

DistributedBoundQp::~DistributedBoundQp() {
  if (petsc_finalized()) return;
  for (Vec& v : near_null_space) VecDestroy(&v);
  for (Vec& v : coarse_near_null_space) VecDestroy(&v);
  if (coarse_interpolation) MatDestroy(&coarse_interpolation);
  if (f) VecDestroy(&f);
  if (b) VecDestroy(&b);
  if (A) MatDestroy(&A);
}

LoadVectorRange set_load_vectors(const DistributedModel& dm, DistributedBoundQp& qp) {
  const Model& model = dm.local;
  // f on the local free DOFs: the forces of this rank's faces and elements (in the DOF frames),
  // then the prescribed displacements' share; summed over the ranks by PETSc.
  Eigen::VectorXd f = Eigen::VectorXd::Zero(model.n_free);
  add_force_loads(model, f);
  add_prescribed_forces(model, f);
  check_petsc(VecSet(qp.f, 0.0), "VecSet");
  std::vector<PetscInt> rows;
  std::vector<PetscScalar> values;
  for (int k = 0; k < model.n_free; ++k)
    if (f[k] != 0) {
      rows.push_back(dm.row_of_free[k]);
      values.push_back(f[k]);
    }
  check_petsc(VecSetValues(qp.f, static_cast<PetscInt>(rows.size()), rows.data(), values.data(), ADD_VALUES),
              "VecSetValues");
  check_petsc(VecAssemblyBegin(qp.f), "VecAssemblyBegin");
  check_petsc(VecAssemblyEnd(qp.f), "VecAssemblyEnd");
  // b = Qᵀ f at the own candidate nodes (their columns are own rows).
  check_petsc(VecCopy(qp.f, qp.b), "VecCopy");
  PetscScalar* b = nullptr;
  VecGetArray(qp.b, &b);
  LoadVectorRange range;
  int finite = 1;
  for (int k = 0; k < dm.n_own_rows; ++k) {
    range.largest = std::max(range.largest, std::abs(b[k]));
    finite = finite && std::isfinite(b[k]);
  }
  for (const NodeTransform& t : qp.transforms) {
    if (t.node >= dm.n_owned) continue;
    Eigen::VectorXd part(t.columns.size());
    for (std::size_t a = 0; a < t.columns.size(); ++a) part[a] = b[dm.local_row(t.columns[a])];
    part = t.Q.transpose() * part;
    for (std::size_t a = 0; a < t.columns.size(); ++a) b[dm.local_row(t.columns[a])] = part[a];
  }
  VecRestoreArray(qp.b, &b);
  MPI_Allreduce(MPI_IN_PLACE, &range.largest, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &finite, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  range.finite = finite != 0;
  // The bounds g_i, in the order of qp.bounded (a candidate's g holds its node's prescribed motion).
  qp.upper.clear();
  for (const NodeTransform& t : qp.transforms) {
    if (t.node >= dm.n_owned) continue;
    for (int a = 0; a < t.n_rows; ++a)
      qp.upper.push_back(contact_row(model, model.candidates[t.first_candidate + a]).g);
  }
  return range;
}

DistributedBoundQp assemble_distributed_bound_qp(const DistributedModel& dm) {
  const Model& model = dm.local;
  const int dim = model.dim;
  DistributedBoundQp qp;
  make_transforms(dm, qp);
  checkpoint();

  std::vector<PetscInt> diagonal, off;
  count_nonzeros(dm, diagonal, off);
  const PetscInt n = static_cast<PetscInt>(dm.n_global_rows), local = dm.n_own_rows;
  check_petsc(MatCreate(PETSC_COMM_WORLD, &qp.A), "MatCreate");
  check_petsc(MatSetSizes(qp.A, local, local, n, n), "MatSetSizes");
  check_petsc(MatSetType(qp.A, MATAIJ), "MatSetType");
  check_petsc(MatSetBlockSize(qp.A, dim), "MatSetBlockSize");
  qp.block_size = dim;
  check_petsc(MatSeqAIJSetPreallocation(qp.A, 0, diagonal.data()), "MatSeqAIJSetPreallocation");
  check_petsc(MatMPIAIJSetPreallocation(qp.A, 0, diagonal.data(), 0, off.data()), "MatMPIAIJSetPreallocation");
  diagonal = {};
  off = {};
  MatSetOption(qp.A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE);

  double largest = 0;
  bool finite = true;
  add_elements(dm, qp, largest, finite);
  check_petsc(MatAssemblyBegin(qp.A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check_petsc(MatAssemblyEnd(qp.A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  MatSetOption(qp.A, MAT_SYMMETRIC, PETSC_TRUE);
  MatSetOption(qp.A, MAT_SPD, PETSC_TRUE);
  double largest_k = largest;
  int k_finite = finite;
  MPI_Allreduce(MPI_IN_PLACE, &largest_k, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &k_finite, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);

  check_petsc(MatCreateVecs(qp.A, &qp.b, &qp.f), "MatCreateVecs");
  // The bounded rows: row a of a node's group bounds its variable a (the first rows of T are
  // the group's rows of B); their bounds follow the loads (set_load_vectors).
  for (const NodeTransform& t : qp.transforms) {
    if (t.node >= dm.n_owned) continue;
    for (int a = 0; a < t.n_rows; ++a) qp.bounded.push_back(dm.row_of_free[t.columns[a]]);
  }
  const LoadVectorRange f = set_load_vectors(dm, qp);
  refuse_unrepresentable(model, largest_k, k_finite, f.largest, f.finite);
  const RigidMotions rigid(dm);
  add_near_null_space(dm, qp, rigid);
  add_coarse_space(dm, qp, rigid);
  return qp;
}

}  // namespace contactqp::detail
