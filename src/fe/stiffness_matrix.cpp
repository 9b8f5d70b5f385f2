// Why not Eigen's setFromTriplets: it keeps the triplets (16 bytes per element entry), a
// transposed copy and then K itself, and its sorting was most of the assembly's time. Here K's
// pattern comes from the mesh (the free DOFs of the nodes sharing an element, which are
// exactly the entries the elements add to), and the element matrices are added into it in
// element order, chunk by chunk: one thread per half of K's columns, so every entry is still
// the sum of its element contributions in element order, as setFromTriplets sums duplicates.
#include "stiffness_matrix.hpp"

#include <algorithm>
#include <thread>
#include <vector>

#include "contactqp/mesh.hpp"
#include "node_elements.hpp"

namespace contactqp::detail {

namespace {

// K_e in the nodes' DOF frames: Tᵀ K_e T with T block-diagonal (identity at most nodes).
void rotate_to_dof_frames(const Model& model, const int* v, int npe, Eigen::MatrixXd& Ke) {
  if (model.frame_of_node.empty()) return;
  bool any = false;
  for (int i = 0; i < npe; ++i) any = any || model.frame_of_node[v[i]] >= 0;
  if (!any) return;
  const int dim = model.dim;
  Eigen::MatrixXd T = Eigen::MatrixXd::Identity(dim * npe, dim * npe);
  for (int i = 0; i < npe; ++i) T.block(dim * i, dim * i, dim, dim) = dof_frame(model, v[i]);
  Ke = T.transpose() * Ke * T;
}

// At most two threads (this machine's cores); one below this many elements per thread.
constexpr unsigned kMaxThreads = 2;
constexpr int kElementsPerThread = 4096;
// Element matrices computed before they are added: bounds the buffer (about 20 MB for 10-node
// tetrahedra) whatever the mesh.
constexpr int kChunk = 2048;

int thread_count(int n_elements) {
  if (n_elements < kElementsPerThread) return 1;
  return static_cast<int>(std::max(1u, std::min(kMaxThreads, std::thread::hardware_concurrency())));
}

// Runs work(t) for t = 0 .. n − 1, t = 0 on the calling thread.
template <class Work>
void in_parallel(int n, const Work& work) {
  std::vector<std::thread> threads;
  for (int t = 1; t < n; ++t) threads.emplace_back(work, t);
  work(0);
  for (std::thread& thread : threads) thread.join();
}

// K's compressed pattern (column starts, row indices ascending), values zero: the entries the
// owned elements add to.
void build_pattern(const Model& model, const std::vector<char>& owned, Eigen::SparseMatrix<double>& K) {
  const Mesh& mesh = model.mesh;
  const int dim = mesh.dim, n_nodes = mesh.n_nodes();
  // Elements at each node, then each node's neighbours: the nodes of those elements.
  const ElementsAtNodes at = elements_at_nodes(mesh, owned);

  std::vector<int> free_of_node(n_nodes, 0);  // free DOFs per node
  for (int n = 0; n < n_nodes; ++n)
    for (int c = 0; c < dim; ++c) free_of_node[n] += model.free_index[dim * n + c] >= 0;

  K.resize(model.n_free, model.n_free);
  std::vector<int> neighbours;
  if (!model.rigid_surfaces.empty()) {
    // A rigid surface's DOFs share a column (model.hpp), and a turning one's also move with its
    // angles' columns: a column's rows are those of all its nodes, and a node's rows no longer
    // ascend with the DOF. Built column by column instead, sorted.
    std::vector<std::vector<int>> rows_of_column(model.n_free);
    for (int n = 0; n < n_nodes; ++n) {
      if (free_of_node[n] == 0 || at.first[n] == at.first[n + 1]) continue;
      neighbours_of(mesh, at, n, neighbours);
      for (int c = 0; c < dim; ++c)
        for_each_column(model, dim * n + c, [&](int column, double) {
          for (int m : neighbours)
            for (int r = 0; r < dim; ++r)
              for_each_column(model, dim * m + r, [&](int row, double) { rows_of_column[column].push_back(row); });
        });
    }
    std::size_t total = 0;
    for (std::vector<int>& rows : rows_of_column) {
      std::sort(rows.begin(), rows.end());
      rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
      total += rows.size();
    }
    K.resizeNonZeros(static_cast<Eigen::Index>(total));
    std::fill(K.valuePtr(), K.valuePtr() + total, 0.0);
    std::size_t at_entry = 0;
    for (int column = 0; column < model.n_free; ++column) {
      K.outerIndexPtr()[column] = static_cast<int>(at_entry);
      std::copy(rows_of_column[column].begin(), rows_of_column[column].end(), K.innerIndexPtr() + at_entry);
      at_entry += rows_of_column[column].size();
    }
    K.outerIndexPtr()[model.n_free] = static_cast<int>(at_entry);
    return;
  }
  std::vector<std::vector<int>> rows_of_node(n_nodes);
  std::size_t nnz = 0;
  for (int n = 0; n < n_nodes; ++n) {
    if (free_of_node[n] == 0 || at.first[n] == at.first[n + 1]) continue;
    neighbours_of(mesh, at, n, neighbours);
    std::vector<int>& rows = rows_of_node[n];
    // free_index increases with the DOF, so the rows come out ascending.
    for (int m : neighbours)
      for (int c = 0; c < dim; ++c)
        if (model.free_index[dim * m + c] >= 0) rows.push_back(model.free_index[dim * m + c]);
    nnz += rows.size() * free_of_node[n];
  }
  K.resizeNonZeros(static_cast<Eigen::Index>(nnz));
  int* outer = K.outerIndexPtr();
  int* inner = K.innerIndexPtr();
  std::fill(K.valuePtr(), K.valuePtr() + nnz, 0.0);
  std::size_t position = 0;
  for (int n = 0; n < n_nodes; ++n)
    for (int c = 0; c < dim; ++c) {
      const int column = model.free_index[dim * n + c];
      if (column < 0) continue;
      outer[column] = static_cast<int>(position);
      std::copy(rows_of_node[n].begin(), rows_of_node[n].end(), inner + position);
      position += rows_of_node[n].size();
    }
  outer[model.n_free] = static_cast<int>(position);
  // Release the per-node lists now, before the values are added.
  std::vector<std::vector<int>>().swap(rows_of_node);
}

}  // namespace

Eigen::MatrixXd dof_frame_rotated(const Model& model, const int* v, int npe, Eigen::MatrixXd Ke) {
  rotate_to_dof_frames(model, v, npe, Ke);
  return Ke;
}

void assemble_stiffness(const Model& model, const std::vector<char>& elements, Eigen::SparseMatrix<double>& K,
                        Eigen::VectorXd& f) {
  const Mesh& mesh = model.mesh;
  const std::vector<ElementLaw> laws = element_laws(model);  // one per body
  const double thickness = model.scene.body.thickness;
  const int npe = mesh.nodes_per_element(), dim = mesh.dim, n = dim * npe;
  const ElementType type = mesh.type();
  const int n_elements = mesh.n_elements();
  const std::vector<char> owned = elements.empty() ? std::vector<char>(n_elements, 1) : elements;
  build_pattern(model, owned, K);
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  double* values = K.valuePtr();

  const int n_threads = thread_count(n_elements);
  std::vector<Eigen::MatrixXd> Ke(std::min(kChunk, n_elements));
  // Columns [column_from[t], column_from[t + 1]) are thread t's to add to.
  std::vector<int> column_from(n_threads + 1);
  for (int t = 0; t <= n_threads; ++t)
    column_from[t] = static_cast<int>(static_cast<long long>(model.n_free) * t / n_threads);
  const auto dofs_of = [&](int e, int* dofs) {
    const int* v = mesh.element(e);
    for (int i = 0; i < npe; ++i)
      for (int c = 0; c < dim; ++c) dofs[dim * i + c] = dim * v[i] + c;
  };
  // f takes every element's prescribed displacements (f is whole in every part of K): an element
  // K does not take still needs its matrix when it has a nonzero one.
  std::vector<char> moves_prescribed(n_elements, 0);
  for (int e = 0; e < n_elements; ++e) {
    if (owned[e]) continue;
    const int* v = mesh.element(e);
    bool free = false, prescribed = false;
    for (int i = 0; i < npe; ++i)
      for (int c = 0; c < dim; ++c) {
        const int dof = dim * v[i] + c;
        free = free || model.free_index[dof] >= 0;
        prescribed = prescribed || (model.free_index[dof] < 0 && model.prescribed[dof] != 0);
      }
    moves_prescribed[e] = free && prescribed;
  }

  for (int start = 0; start < n_elements; start += kChunk) {
    const int end = std::min(n_elements, start + kChunk);
    in_parallel(n_threads, [&](int t) {  // the element matrices of the chunk
      std::vector<Eigen::Vector3d> coordinates(npe);
      for (int e = start + (end - start) * t / n_threads; e < start + (end - start) * (t + 1) / n_threads; ++e) {
        if (!owned[e] && !moves_prescribed[e]) continue;
        const int* v = mesh.element(e);
        for (int i = 0; i < npe; ++i) coordinates[i] = mesh.nodes[v[i]];
        Ke[e - start] = dof_frame_rotated(
            model, v, npe, element_stiffness(type, coordinates.data(), laws[body_of_element(model, e)], thickness));
      }
    });
    in_parallel(n_threads, [&](int t) {  // added in element order, each thread to its own columns
      std::vector<int> dofs(n);
      for (int e = start; e < end; ++e) {
        if (!owned[e]) continue;
        dofs_of(e, dofs.data());
        const Eigen::MatrixXd& k = Ke[e - start];
        if (model.levers.empty()) {
          for (int j = 0; j < n; ++j) {
            const int column = model.free_index[dofs[j]];
            if (column < column_from[t] || column >= column_from[t + 1]) continue;
            const int* rows = inner + outer[column];
            const int* rows_end = inner + outer[column + 1];
            for (int i = 0; i < n; ++i) {
              const int row = model.free_index[dofs[i]];
              if (row < 0) continue;
              values[std::lower_bound(rows, rows_end, row) - inner] += k(i, j);
            }
          }
          continue;
        }
        // A turning surface: each DOF's row and column go to every column it moves with (TᵀKT).
        for (int j = 0; j < n; ++j)
          for_each_column(model, dofs[j], [&](int column, double w_j) {
            if (column < column_from[t] || column >= column_from[t + 1]) return;
            const int* rows = inner + outer[column];
            const int* rows_end = inner + outer[column + 1];
            for (int i = 0; i < n; ++i)
              for_each_column(model, dofs[i], [&](int row, double w_i) {
                values[std::lower_bound(rows, rows_end, row) - inner] += w_i * k(i, j) * w_j;
              });
          });
      }
    });
    // The prescribed displacements to the right-hand side, in the serial loop's order.
    std::vector<int> dofs(n);
    for (int e = start; e < end; ++e) {
      if (!owned[e] && !moves_prescribed[e]) continue;
      dofs_of(e, dofs.data());
      const Eigen::MatrixXd& k = Ke[e - start];
      for (int i = 0; i < n; ++i)
        for_each_column(model, dofs[i], [&](int row, double w) {
          for (int j = 0; j < n; ++j)
            if (model.free_index[dofs[j]] < 0) f[row] -= w * k(i, j) * model.prescribed[dofs[j]];
        });
    }
  }
}

void add_prescribed_forces(const Model& model, Eigen::VectorXd& f) {
  const Mesh& mesh = model.mesh;
  const std::vector<ElementLaw> laws = element_laws(model);
  const int npe = mesh.nodes_per_element(), dim = mesh.dim;
  std::vector<Eigen::Vector3d> coordinates(npe);
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    bool loaded = false;
    for (int i = 0; i < npe; ++i)
      for (int c = 0; c < dim; ++c)
        loaded = loaded || (model.free_index[dim * v[i] + c] < 0 && model.prescribed[dim * v[i] + c] != 0);
    if (!loaded) continue;
    for (int i = 0; i < npe; ++i) coordinates[i] = mesh.nodes[v[i]];
    const Eigen::MatrixXd k =
        dof_frame_rotated(model, v, npe,
                          element_stiffness(mesh.type(), coordinates.data(), laws[body_of_element(model, e)],
                                            model.scene.body.thickness));
    for (int i = 0; i < dim * npe; ++i)
      for_each_column(model, dim * v[i / dim] + i % dim, [&](int row, double w) {
        for (int j = 0; j < dim * npe; ++j) {
          const int dof = dim * v[j / dim] + j % dim;
          if (model.free_index[dof] < 0) f[row] -= w * k(i, j) * model.prescribed[dof];
        }
      });
  }
}

Eigen::VectorXd prescribed_forces(const Model& model) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(model.n_free);
  add_prescribed_forces(model, f);
  return f;
}

}  // namespace contactqp::detail
