// Post-processing of a distributed solution (distributed_post.hpp).
#include "distributed_post.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <unordered_map>

#include "contact/contact.hpp"
#include "contactqp/phases.hpp"
#include "contactqp/temporary_file.hpp"
#include "world.hpp"

namespace contactqp::detail {
namespace {

// Every rank's values on rank 0, in rank order (MPI_Gatherv); `counts` receives each rank's.
template <class T>
std::vector<T> gather_on_zero(const std::vector<T>& mine, MPI_Datatype type, std::vector<int>* counts = nullptr) {
  const int ranks = world_size();
  int count = static_cast<int>(mine.size());
  std::vector<int> all_counts(ranks), offsets(ranks, 0);
  MPI_Gather(&count, 1, MPI_INT, all_counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  for (int r = 1; r < ranks; ++r) offsets[r] = offsets[r - 1] + all_counts[r - 1];
  std::vector<T> all(world_rank() == 0 ? offsets.back() + all_counts.back() : 0);
  MPI_Gatherv(mine.data(), count, type, all.data(), all_counts.data(), offsets.data(), type, 0, MPI_COMM_WORLD);
  if (counts) *counts = all_counts;
  return all;
}

// The owner's value of a per-node array (width entries per node) on every holder.
Eigen::VectorXd from_owner(const DistributedModel& model, Eigen::VectorXd values, int width) {
  model.shared.from_owner(values.data(), width);
  return values;
}

}  // namespace

Eigen::VectorXd local_free_values(const DistributedModel& model, const Eigen::VectorXd& own) {
  const Model& local = model.local;
  const int dim = local.dim, n = local.mesh.n_nodes();
  Eigen::VectorXd per_node = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(dim) * n);
  for (int dof = 0; dof < dim * model.n_owned; ++dof)
    if (local.free_index[dof] >= 0) per_node[dof] = own[local.free_index[dof]];
  per_node = from_owner(model, per_node, dim);
  Eigen::VectorXd out(local.n_free);
  for (int dof = 0; dof < dim * n; ++dof)
    if (local.free_index[dof] >= 0) out[local.free_index[dof]] = per_node[dof];
  return out;
}

ContactSurface gather_contact_surface(const DistributedModel& model, const Eigen::VectorXd& own_lambda) {
  const Model& local = model.local;
  const Mesh& mesh = local.mesh;
  // Each own row: its node's global number, obstacle, gap, tributary, λ and position.
  std::vector<int> rows;
  std::vector<double> numbers;
  for (int i = 0; i < model.n_own_candidates; ++i) {
    const Candidate& c = local.candidates[i];
    rows.insert(rows.end(), {model.global_node[c.node], c.obstacle});
    numbers.insert(numbers.end(), {c.gap, c.tributary, own_lambda[i]});
    for (int k = 0; k < 3; ++k) numbers.push_back(mesh.nodes[c.node][k]);
  }
  // The contact boundary's faces of this rank that touch a candidate, and their nodes.
  std::vector<char> is_candidate(mesh.n_nodes(), 0);
  for (const Candidate& c : local.candidates) is_candidate[c.node] = 1;
  std::vector<int> faces, face_nodes;
  std::vector<double> positions;
  std::vector<char> listed(mesh.n_nodes(), 0);
  const auto boundary = mesh.boundaries.find(local.scene.contact.boundary);
  if (boundary != mesh.boundaries.end())
    for (const BoundaryFace& face : boundary->second) {
      if (std::none_of(face.nodes.begin(), face.nodes.begin() + face.n_nodes,
                       [&](int node) { return is_candidate[node]; }))
        continue;
      faces.push_back(face.n_nodes);
      for (int k = 0; k < face.n_nodes; ++k) {
        const int node = face.nodes[k];
        faces.push_back(model.global_node[node]);
        if (listed[node]) continue;
        listed[node] = 1;
        face_nodes.push_back(model.global_node[node]);
        for (int c = 0; c < 3; ++c) positions.push_back(mesh.nodes[node][c]);
      }
    }
  const std::vector<int> all_rows = gather_on_zero(rows, MPI_INT);
  const std::vector<double> all_numbers = gather_on_zero(numbers, MPI_DOUBLE);
  const std::vector<int> all_faces = gather_on_zero(faces, MPI_INT);
  const std::vector<int> all_face_nodes = gather_on_zero(face_nodes, MPI_INT);
  const std::vector<double> all_positions = gather_on_zero(positions, MPI_DOUBLE);

  ContactSurface surface;
  if (world_rank() != 0) return surface;
  auto surface_model = std::make_shared<Model>();
  Model& out = *surface_model;
  out.scene = local.scene;
  out.rotation = local.rotation;
  out.dim = local.dim;
  out.max_gap = local.max_gap;
  out.max_gap_rule = local.max_gap_rule;
  out.mesh.dim = mesh.dim;
  out.mesh.order = mesh.order;
  std::unordered_map<int, int> surface_node;  // global node -> surface node
  const auto node_of = [&](int global, const double* x) {
    const auto [it, inserted] = surface_node.emplace(global, out.mesh.n_nodes());
    if (inserted) out.mesh.nodes.emplace_back(x[0], x[1], x[2]);
    return it->second;
  };
  const std::size_t m = all_rows.size() / 2;
  surface.lambda.resize(static_cast<Eigen::Index>(m));
  for (std::size_t i = 0; i < m; ++i) {
    const double* row = all_numbers.data() + 6 * i;
    Candidate c;
    c.node = node_of(all_rows[2 * i], row + 3);
    c.obstacle = all_rows[2 * i + 1];
    c.gap = row[0];
    c.tributary = row[1];
    surface.lambda[static_cast<Eigen::Index>(i)] = row[2];
    out.candidates.push_back(c);
  }
  for (std::size_t k = 0; k < all_face_nodes.size(); ++k) node_of(all_face_nodes[k], all_positions.data() + 3 * k);
  std::vector<BoundaryFace>& contact_faces = out.mesh.boundaries[local.scene.contact.boundary];
  for (std::size_t k = 0; k < all_faces.size();) {
    BoundaryFace face;
    face.n_nodes = all_faces[k++];
    for (int j = 0; j < face.n_nodes; ++j) face.nodes[j] = surface_node.at(all_faces[k++]);
    contact_faces.push_back(face);
  }
  auto qp = std::make_shared<QuadraticProgram>();
  qp->B.resize(static_cast<Eigen::Index>(m), 0);
  qp->g = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(m));
  for (const Candidate& c : out.candidates) qp->rows.push_back({c.node, c.obstacle, c.pair});
  surface.model = surface_model;
  surface.qp = qp;
  return surface;
}

ContactSummary distributed_contact_summary(const DistributedModel& model, const ContactSurface& surface,
                                           const Eigen::VectorXd& displacement, std::vector<double>& own_pressure) {
  ContactSummary summary;
  std::vector<double> pressure;
  if (surface.model) {
    summary = summarize_contact_rows(*surface.model, *surface.qp, surface.lambda);
    pressure = nodal_pressures(*surface.model, *surface.qp, surface.lambda);
  }
  // Each rank's rows' pressures back to it (the gathered order is the rank order).
  const int ranks = world_size();
  std::vector<int> counts(ranks), offsets(ranks, 0);
  const int mine = model.n_own_candidates;
  MPI_Gather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  for (int r = 1; r < ranks; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  own_pressure.resize(mine);
  MPI_Scatterv(pressure.data(), counts.data(), offsets.data(), MPI_DOUBLE, own_pressure.data(), mine, MPI_DOUBLE, 0,
               MPI_COMM_WORLD);

  // Boundary nodes outside the candidate set that entered an obstacle: each own node of the
  // whole body's outer boundary once, the tolerance from the whole displacement.
  const Mesh& mesh = model.local.mesh;
  std::vector<char> seen(mesh.n_nodes(), 0);
  std::vector<int> nodes;
  for (const BoundaryFace& face : model.outer)
    for (int k = 0; k < face.n_nodes; ++k) {
      const int node = face.nodes[k];
      if (node < model.n_owned && !seen[node]) {
        seen[node] = 1;
        nodes.push_back(node);
      }
    }
  double largest = displacement.size() ? displacement.cwiseAbs().maxCoeff() : 0.0;
  MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  ContactSummary counted;
  count_penetrating(model.local, displacement, nodes, 1e-6 * std::max(largest, 1e-300), counted);
  int count = counted.penetrating_non_candidates;
  double deepest = counted.max_non_candidate_penetration;
  MPI_Reduce(world_rank() == 0 ? MPI_IN_PLACE : &count, &count, 1, MPI_INT, MPI_SUM, 0, MPI_COMM_WORLD);
  MPI_Reduce(world_rank() == 0 ? MPI_IN_PLACE : &deepest, &deepest, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
  summary.penetrating_non_candidates = count;
  summary.max_non_candidate_penetration = deepest;
  return summary;
}

std::vector<Reaction> distributed_reactions(const DistributedModel& model, const Eigen::VectorXd& local_u,
                                            const Eigen::VectorXd& own_lambda) {
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(model.local.candidates.size()));
  lambda.head(model.n_own_candidates) = own_lambda;  // the other ranks' rows are theirs to count
  std::vector<Reaction> out =
      reactions(model.local, local_u, lambda, [&model](const std::string& name) { return model.nodes_of(name); });
  std::vector<double> forces;
  for (const Reaction& r : out) forces.insert(forces.end(), {r.force.x(), r.force.y(), r.force.z()});
  MPI_Allreduce(MPI_IN_PLACE, forces.data(), static_cast<int>(forces.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k].force = Eigen::Vector3d(forces[3 * k], forces[3 * k + 1], forces[3 * k + 2]);
  return out;
}

std::vector<PointArray> PieceArrays::arrays() const {
  Model shape;  // solution_arrays() reads the model's dimension only
  shape.dim = dim;
  return solution_arrays(shape, displacement, stress, contact);
}

PieceArrays piece_arrays(const DistributedModel& model, const Eigen::VectorXd& displacement,
                         const Eigen::VectorXd& local_u, const Eigen::VectorXd& own_lambda,
                         const std::vector<double>& own_pressure) {
  const Model& local = model.local;
  const Mesh& mesh = local.mesh;
  const int n = mesh.n_nodes(), dim = local.dim;
  PieceArrays piece;
  piece.dim = dim;
  piece.displacement = displacement;
  // Stresses: the element sums of every rank at a node, then the average.
  const StressSums sums = stress_sums(local, displacement);
  Eigen::MatrixXd packed(7, n);
  packed.topRows(6) = sums.sum;
  packed.row(6) = sums.weight.transpose();
  model.shared.sum(packed.data(), 7);
  StressSums all{packed.topRows(6), packed.row(6).transpose()};
  piece.stress = nodal_stresses(all, dim);

  // Contact fields of the own nodes (every row of an own node is own), then from the owner.
  ContactFields& fields = piece.contact;
  fields.pressure = Eigen::VectorXd::Zero(n);
  fields.force = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(dim) * n);
  fields.mask = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd gap = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  std::vector<char> candidate(n, 0);
  const Eigen::VectorXd slack = row_slacks(local, local_u);
  for (int i = 0; i < model.n_own_candidates; ++i) {
    const Candidate& c = local.candidates[i];
    gap[c.node] = std::min(gap[c.node], slack[i]);
    fields.pressure[c.node] += own_pressure[i];
    const Eigen::Vector3d normal = project(local.scene.obstacles[c.obstacle], mesh.nodes[c.node]).normal;
    fields.force.segment(dim * c.node, dim) += own_lambda[i] * normal.head(dim);
    candidate[c.node] = 1;
  }
  for (int node : model.nodes_of(local.scene.contact.boundary)) {
    fields.mask[node] = 1;
    if (node >= model.n_owned || candidate[node]) continue;
    Eigen::Vector3d moved = mesh.nodes[node];
    moved.head(dim) += displacement.segment(dim * node, dim);
    for (const ObstacleSpec& obstacle : local.scene.obstacles)
      gap[node] = std::min(gap[node], project(obstacle, moved).gap);
  }
  fields.gap = gap.unaryExpr([](double g) { return std::isfinite(g) ? g : 0.0; });
  fields.pressure = from_owner(model, fields.pressure, 1);
  fields.force = from_owner(model, fields.force, dim);
  fields.gap = from_owner(model, fields.gap, 1);
  return piece;
}

Eigen::VectorXd row_slacks(const Model& local, const Eigen::VectorXd& local_u) {
  Eigen::VectorXd slack(local.candidates.size());
  for (std::size_t i = 0; i < local.candidates.size(); ++i) {
    const ContactRowEntries row = contact_row(local, local.candidates[i]);
    double Bu = 0;
    for (const auto& [column, value] : row.coefficients) Bu += value * local_u[column];
    slack[static_cast<Eigen::Index>(i)] = row.g - Bu;
  }
  return slack;
}

void write_pvtu(const std::string& pvtu_path, const Mesh& mesh, const std::vector<PointArray>& arrays,
                const std::vector<PointArray>& cell_arrays) {
  namespace fs = std::filesystem;
  const int rank = world_rank(), ranks = world_size();
  if (ranks == 1 && fs::path(pvtu_path).extension() != ".pvtu") {
    write_file_atomically(pvtu_path, vtu_piece(mesh, arrays, cell_arrays));
    return;
  }
  const fs::path target(pvtu_path);
  const std::string stem = target.stem().string();
  const auto piece_name = [&stem](int r) { return stem + "_" + std::to_string(r) + ".vtu"; };
  const std::string piece = (target.parent_path() / piece_name(rank)).string();
  std::unique_ptr<TemporaryFile> staged;  // removed unless committed
  try {
    // Each step ends where the ranks agree that none failed (run/phases.hpp).
    staged = std::make_unique<TemporaryFile>(piece);
    staged->write(vtu_piece(mesh, arrays, cell_arrays));
    checkpoint();
    staged->commit();
    checkpoint();
    if (rank == 0) {
      std::vector<std::string> pieces;
      for (int r = 0; r < ranks; ++r) pieces.push_back(piece_name(r));
      write_file_atomically(pvtu_path, pvtu_document(arrays, pieces, cell_arrays));
    }
    checkpoint();
  } catch (...) {
    // Some rank could not write: no piece of this run stays.
    staged.reset();
    std::error_code ignored;
    fs::remove(piece, ignored);
    throw;
  }
}

}  // namespace contactqp::detail
