// build_distributed_model() (distributed_model.hpp): build_model()'s steps on each rank's part,
// with the sums over the ranks that make the parts agree.
#include "distributed_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/contact.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/phases.hpp"
#include "model/model_parts.hpp"
#include "run/distributed_run.hpp"
#include "world.hpp"

namespace contactqp::detail {
namespace {

// Which boundaries each node lies on, from the faces of every rank.
void mark_boundaries(DistributedModel& out) {
  const Mesh& mesh = out.local.mesh;
  out.boundary_names.clear();
  for (const auto& [name, faces] : mesh.boundaries) out.boundary_names.push_back(name);
  out.mask_words = std::max<int>(1, (static_cast<int>(out.boundary_names.size()) + 30) / 31);
  out.boundary_mask.assign(static_cast<std::size_t>(out.mask_words) * mesh.n_nodes(), 0);
  for (std::size_t b = 0; b < out.boundary_names.size(); ++b)
    for (const BoundaryFace& face : mesh.boundaries.at(out.boundary_names[b]))
      for (int k = 0; k < face.n_nodes; ++k)
        out.boundary_mask[static_cast<std::size_t>(face.nodes[k]) * out.mask_words + b / 31] |= 1 << (b % 31);
  out.shared.bitwise_or(out.boundary_mask.data(), out.mask_words);
}

// The candidates of the contact boundary, from its normals and tributaries summed over the ranks.
std::vector<Candidate> distributed_candidates(const DistributedModel& out, const Scene& scene, double max_gap) {
  const Model& model = out.local;
  const int n = model.mesh.n_nodes();
  const std::string& boundary = scene.contact.boundary;
  const BoundaryNodeGeometry sums = boundary_sums(model.mesh, boundary);
  std::vector<double> per_node(4 * static_cast<std::size_t>(n), 0.0);
  for (std::size_t k = 0; k < sums.nodes.size(); ++k) {
    for (int c = 0; c < 3; ++c) per_node[4 * sums.nodes[k] + c] = sums.normals[k][c];
    per_node[4 * sums.nodes[k] + 3] = sums.tributary[k];
  }
  out.shared.sum(per_node.data(), 4);
  BoundaryNodeGeometry geometry;
  for (int node : out.nodes_of(boundary)) {
    geometry.nodes.push_back(node);
    geometry.normals.emplace_back(per_node[4 * node], per_node[4 * node + 1], per_node[4 * node + 2]);
    geometry.tributary.push_back(per_node[4 * node + 3]);
  }
  normalise_normals(geometry);
  return select_candidates(model.mesh, scene.obstacles, geometry, max_gap);
}

// Point loads: the node of each (its named point, or the nearest node of the whole mesh, the
// lowest rank's on a tie), on the rank that owns it; −1 elsewhere and for other loads.
std::vector<int> distributed_point_nodes(const DistributedModel& out, const Scene& scene,
                                         std::vector<std::string>& warnings) {
  const Mesh& mesh = out.local.mesh;
  std::vector<int> nodes(scene.loads.size(), -1);
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), high = -low;
  for (int k = 0; k < out.n_owned; ++k) low = low.cwiseMin(mesh.nodes[k]), high = high.cwiseMax(mesh.nodes[k]);
  MPI_Allreduce(MPI_IN_PLACE, low.data(), 3, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, high.data(), 3, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  const double extent = (high - low).norm();
  for (std::size_t l = 0; l < scene.loads.size(); ++l) {
    const PointLoad* point = scene.loads[l].as<PointLoad>();
    if (!point) continue;
    if (!point->point.empty()) {
      for (int node : mesh.points.at(point->point))
        if (node < out.n_owned && nodes[l] < 0) nodes[l] = node;
      continue;
    }
    struct {
      double distance;
      int rank;
    } mine{std::numeric_limits<double>::infinity(), world_rank()}, best{};
    int closest = -1;
    for (int node = 0; node < out.n_owned; ++node) {
      const double distance = (mesh.nodes[node] - *point->at).norm();
      if (distance < mine.distance) mine.distance = distance, closest = node;
    }
    MPI_Allreduce(&mine, &best, 1, MPI_DOUBLE_INT, MPI_MINLOC, MPI_COMM_WORLD);
    if (best.rank == world_rank()) nodes[l] = closest;
    if (best.distance > 1e-9 * extent) {
      Eigen::Vector3d at = Eigen::Vector3d::Zero();
      int number = -1;
      if (best.rank == world_rank()) at = mesh.nodes[closest], number = out.global_node[closest];
      MPI_Bcast(at.data(), 3, MPI_DOUBLE, best.rank, MPI_COMM_WORLD);
      MPI_Bcast(&number, 1, MPI_INT, best.rank, MPI_COMM_WORLD);
      warnings.push_back(scene.loads[l].path + " acts at node " + std::to_string(number) + " at " +
                         format_point(at, mesh.dim) + ", " + format_value(best.distance) +
                         " from the point asked for (the nearest node)");
    }
  }
  return nodes;
}

// The consistent nodal forces of this rank's faces and elements, and the point loads on the
// nodes it owns (a share of the force for a node on symmetry planes, as nodal_forces() gives):
// of every load, or of load `only` alone (a load step's share).
constexpr std::size_t kEveryLoad = static_cast<std::size_t>(-1);
Eigen::VectorXd distributed_nodal_forces(const DistributedModel& out, const std::vector<int>& point_nodes,
                                         std::size_t only = kEveryLoad) {
  const Model& model = out.local;
  const auto counted = [only](std::size_t l) { return only == kEveryLoad || l == only; };
  Scene without_points = model.scene;
  std::vector<LoadSpec> loads;
  for (std::size_t l = 0; l < model.scene.loads.size(); ++l)
    if (counted(l) && !model.scene.loads[l].as<PointLoad>()) loads.push_back(model.scene.loads[l]);
  without_points.loads = loads;
  Eigen::VectorXd f = nodal_forces(without_points, model.mesh, std::vector<int>(loads.size(), -1));
  const int dim = model.dim;
  for (std::size_t l = 0; l < model.scene.loads.size(); ++l) {
    const PointLoad* point = model.scene.loads[l].as<PointLoad>();
    if (!point || point_nodes[l] < 0 || !counted(l)) continue;
    int planes = 0;
    for (const std::string& plane : symmetry_boundaries(model.scene.body, dim))
      planes += out.on_boundary(point_nodes[l], plane);
    f.segment(dim * point_nodes[l], dim) += std::pow(0.5, planes) * point->force.head(dim);
  }
  return f;
}

// Rows of the nodes with a free DOF (dim each) and contact rows of the candidates: each rank's
// own consecutive.
void number_rows(DistributedModel& out) {
  Model& model = out.local;
  const int dim = model.dim, n = model.mesh.n_nodes();
  const auto has_free = [&](int node) {
    for (int c = 0; c < dim; ++c)
      if (model.free_index[dim * node + c] >= 0) return true;
    return false;
  };
  out.n_own_dofs = 0;
  for (int dof = 0; dof < dim * out.n_owned; ++dof) out.n_own_dofs += model.free_index[dof] >= 0;
  out.n_global_dofs = out.n_own_dofs;
  MPI_Allreduce(MPI_IN_PLACE, &out.n_global_dofs, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  long long own_nodes = 0, all_nodes = 0;
  for (int node = 0; node < out.n_owned; ++node) own_nodes += has_free(node);
  const long long first_node = first_of_mine(own_nodes, &all_nodes);
  out.first_row = static_cast<PetscInt>(dim * first_node);
  out.n_own_rows = static_cast<int>(dim * own_nodes);
  out.n_global_rows = dim * all_nodes;
  std::vector<int> rows(n, -1);
  for (int node = 0, next = static_cast<int>(out.first_row); node < out.n_owned; ++node)
    if (has_free(node)) rows[node] = next, next += dim;
  out.shared.from_owner(rows.data(), 1);
  out.node_row.assign(rows.begin(), rows.end());
  out.row_of_free.assign(model.n_free, -1);
  for (int dof = 0; dof < dim * n; ++dof)
    if (model.free_index[dof] >= 0) out.row_of_free[model.free_index[dof]] = rows[dof / dim] + dof % dim;

  out.n_own_candidates = 0;
  for (const Candidate& candidate : model.candidates) out.n_own_candidates += candidate.node < out.n_owned;
  out.first_candidate = static_cast<PetscInt>(first_of_mine(out.n_own_candidates, &out.n_global_candidates));
}

}  // namespace

std::vector<int> DistributedModel::nodes_of(const std::string& boundary) const {
  std::vector<int> nodes;
  for (int node = 0; node < local.mesh.n_nodes(); ++node)
    if (on_boundary(node, boundary)) nodes.push_back(node);
  return nodes;
}

bool DistributedModel::on_boundary(int node, const std::string& boundary) const {
  const auto it = std::find(boundary_names.begin(), boundary_names.end(), boundary);
  if (it == boundary_names.end()) return false;
  const std::size_t b = it - boundary_names.begin();
  return boundary_mask[static_cast<std::size_t>(node) * mask_words + b / 31] >> (b % 31) & 1;
}

DistributedModel build_distributed_model(const Scene& scene, const BuildOptions& options,
                                         const std::function<void(const char* phase)>& on_phase) {
  if (!scene.bodies.empty())
    throw InputError("bodies", "a scene with several bodies is solved on one process or with its mesh on every rank");
  DistributedModel out;
  Model& model = out.local;
  choose_max_gap(scene, model);

  Stopwatch clock;
  // What needs the whole body is checked on the coarse mesh, before it is split: the scene's
  // names, conflicting conditions and rigid motions (the refined mesh has the same boundaries).
  const auto check_coarse = [&scene, &model](const Mesh& coarse) {
    check_mesh_names(scene, coarse);
    Model probe;
    probe.mesh = coarse;
    probe.scene = scene;
    probe.scene.transform = TransformSpec{};
    probe.dim = coarse.dim;
    probe.max_gap = model.max_gap;
    apply_displacement_conditions(probe, scene, Eigen::Matrix3d::Identity());
    // A free motion the load drives and no row sees is refused as one process refuses it; one
    // that the contacts hold, which one process solves on its free modes, is not solved here yet.
    probe.candidates = select_candidates(coarse, scene.obstacles, scene.contact.boundary, probe.max_gap);
    remove_prescribed_candidates(probe);
    const Eigen::MatrixXd held = motions_held_by_contact(probe, [&] {
      std::vector<std::string> ignored;
      return Eigen::VectorXd(nodal_forces(probe.scene, coarse, point_load_nodes(scene, coarse, ignored)));
    });
    if (held.cols() > 0) {
      const RigidFreedom freedom = rigid_freedom(probe);
      for (const PartFreedom& part : freedom.parts)
        if (part.null.cols() > 0)
          refuse_held_by_contact_on_several_processes(Backend::Petsc, describe_motion(probe, part, part.null.col(0)));
    }
  };
  MeshPart part = distribute_body_mesh(scene, model.max_gap, options, check_coarse);
  model.mesh = std::move(part.mesh);
  out.outer = std::move(part.outer);
  out.n_owned = part.n_owned;
  out.global_node = std::move(part.global_node);
  out.n_global_nodes = part.n_global_nodes;
  out.n_global_elements = part.n_global_elements;
  out.shared = std::move(part.shared);
  model.timings.add("mesh", clock.seconds());
  if (on_phase) on_phase("model");

  clock.restart();
  model.scene = scene;
  model.scene.transform = TransformSpec{};
  model.dim = model.mesh.dim;
  mark_boundaries(out);
  const NodesOfBoundary nodes_of = [&out](const std::string& name) { return out.nodes_of(name); };
  std::vector<int> point_nodes;
  // In the scene's own frame, as build_model() decides the problem's structure.
  apply_displacement_conditions(model, scene, Eigen::Matrix3d::Identity(), nodes_of);
  model.candidates = distributed_candidates(out, scene, model.max_gap);
  remove_prescribed_candidates(model);
  checkpoint();
  point_nodes = distributed_point_nodes(out, scene, model.warnings);
  model.rotation = scene.transform.rotation();
  model.scene = rotated(scene);
  rotate_mesh(model.mesh, model.rotation);
  apply_displacement_conditions(model, scene, model.rotation, nodes_of);
  checkpoint();
  model.nodal_force = distributed_nodal_forces(out, point_nodes);
  // Load steps: each load's share, as build_model() keeps it (apply_load_step scales them).
  if (!scene.steps.empty())
    model.load_shares = load_shares(
        model, nodes_of, [&out, &point_nodes](std::size_t l) { return distributed_nodal_forces(out, point_nodes, l); });
  warn_near_incompressible(scene, model.mesh, model.warnings);
  number_rows(out);
  model.timings.add("model", clock.seconds());
  return out;
}

}  // namespace contactqp::detail
