// From a scene to a model: the candidate distance, the mesh, boundary conditions, loads and
// contact candidates — all built in the scene's own frame, then turned by its transform.
#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/contact.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/mesh_file.hpp"
#include "model_parts.hpp"

namespace contactqp {
namespace {

// Candidates are the nodes whose initial gap is at most this many times the largest
// prescribed displacement: the body cannot approach an obstacle by much more than it is
// pushed, and the margin covers the local deformation near the contact zone.
constexpr double kLoadGapFactor = 1.5;

// Above these Poisson's ratios the displacement formulation's error from locking shows at
// the percent level on Hertz's problem (docs/incompressible.md).
constexpr double kLinearLockingNu = 0.45;
constexpr double kQuadraticLockingNu = 0.49;

}  // namespace

namespace detail {

// Displacement-based triangles lock as ν → 0.5 in plane strain: the element cannot change
// shape without changing volume, so the body comes out too stiff. Say so, and what helps.
void warn_near_incompressible(const Scene& scene, const Mesh& mesh, std::vector<std::string>& warnings) {
  if (scene.model == ElasticModel::Solid) {
    // Tetrahedra lock as triangles do; there is no mixed formulation for them yet.
    if ((mesh.order == 1 && scene.material.nu > kLinearLockingNu) ||
        (mesh.order == 2 && scene.material.nu > kQuadraticLockingNu))
      warnings.push_back(
          "material.nu = " + format_value(scene.material.nu) + " with " + (mesh.order == 1 ? "4-node" : "10-node") +
          " tetrahedra: they lock as nu -> 0.5 (too stiff: the force for a prescribed push is overstated)");
    return;
  }
  if (scene.model != ElasticModel::PlaneStrain || scene.body.formulation == Formulation::Mixed) return;
  const double nu = scene.material.nu;
  const std::string value = "material.nu = " + format_value(nu);
  if (mesh.order == 1 && nu > kLinearLockingNu)
    warnings.push_back(value +
                       " with 3-node triangles in plane strain: they lock as nu -> 0.5 (too stiff: the force "
                       "for a prescribed push is overstated); use \"formulation\": \"mixed\" under body "
                       "(6-node triangles with a condensed pressure)");
  else if (mesh.order == 2 && nu > kQuadraticLockingNu)
    warnings.push_back(value +
                       " with 6-node triangles in plane strain: they stiffen as nu -> 0.5; "
                       "\"formulation\": \"mixed\" under body removes the locking");
}

void rotate_mesh(Mesh& mesh, const Eigen::Matrix3d& rotation) {
  if (mesh.dim == 2) {
    // A rotation about z: the 2 × 2 block on (x, y), so that z stays exactly 0.
    const Eigen::Matrix2d R = rotation.topLeftCorner<2, 2>();
    for (Eigen::Vector3d& x : mesh.nodes) x.head<2>() = R * x.head<2>();
    return;
  }
  for (Eigen::Vector3d& x : mesh.nodes) x = rotation * x;
}

// The candidate distance: the scene's, or one that follows from the loads. A force load
// gives no displacement scale before the solve (and K may be singular without contact), so
// then every facing node of the contact boundary is a candidate.
void choose_max_gap(const Scene& scene, Model& model) {
  if (scene.contact.max_gap) {
    model.max_gap = *scene.contact.max_gap;
    model.max_gap_rule = "contact.max_gap";
    return;
  }
  double largest = -1;
  bool forces = false;
  for (const LoadSpec& load : scene.loads) {
    forces = forces || load.is_force();
    const DisplacementLoad* d = load.as<DisplacementLoad>();
    if (!d) continue;
    const double ux = d->value[0].value_or(0.0), uy = d->value[1].value_or(0.0), uz = d->value[2].value_or(0.0);
    largest = std::max(largest, uz == 0.0 ? std::hypot(ux, uy) : std::hypot(ux, uy, uz));
  }
  if (largest >= 0 && !forces) {
    model.max_gap = kLoadGapFactor * largest;
    model.max_gap_rule = "1.5 × the largest prescribed displacement";
  } else {
    model.max_gap = std::numeric_limits<double>::infinity();
    model.max_gap_rule = forces ? "every boundary node facing an obstacle (the loads include forces)"
                                : "every boundary node facing an obstacle";
  }
}

}  // namespace detail

Eigen::MatrixXd dof_frame(const Model& model, int node) {
  if (model.frame_of_node.empty() || model.frame_of_node[node] < 0)
    return Eigen::MatrixXd::Identity(model.dim, model.dim);
  return model.frames[model.frame_of_node[node]];
}

Mesh scene_mesh(const Scene& scene, const BuildOptions& options) {
  Model model;
  detail::choose_max_gap(scene, model);  // the fine zone of a generated shape depends on it
  return detail::mesh_body(scene, model.max_gap, options);
}

Model build_model(const Scene& scene, const BuildOptions& options) {
  if (!scene.bodies.empty()) return detail::build_bodies_model(scene, options);
  Model model;
  detail::choose_max_gap(scene, model);

  // Everything that decides the discrete problem's structure — mesh, prescribed DOFs,
  // candidates, point-load nodes — is decided in the scene's own frame, so that a rotated
  // scene has exactly the same structure and differs only by round-off in its numbers.
  Stopwatch clock;
  model.mesh = detail::mesh_body(scene, model.max_gap, options);
  model.timings.add("mesh", clock.seconds());

  clock.restart();
  detail::check_mesh_names(scene, model.mesh);
  model.scene = scene;
  model.scene.transform = TransformSpec{};
  model.dim = model.mesh.dim;
  detail::apply_displacement_conditions(model, scene, Eigen::Matrix3d::Identity());
  model.candidates = detail::select_candidates(model.mesh, scene.obstacles, scene.contact.boundary, model.max_gap);
  detail::remove_prescribed_candidates(model);
  const std::vector<int> point_nodes = detail::point_load_nodes(scene, model.mesh, model.warnings);
  // Rigid motions the prescribed displacements leave free: held by the contacts, or refused
  // (in the scene's own axes, which the message names) when the load drives one no row sees.
  const Eigen::MatrixXd free_motions = detail::motions_held_by_contact(model, [&] {
    return Eigen::VectorXd(detail::nodal_forces(model.scene, model.mesh, point_nodes) +
                           detail::rigid_surface_forces(model));
  });

  // Now turn the scene: nodes, obstacles and load vectors; prescribed components keep the
  // scene's axes through DOF frames.
  model.rotation = scene.transform.rotation();
  model.scene = rotated(scene);
  detail::rotate_mesh(model.mesh, model.rotation);
  detail::apply_displacement_conditions(model, scene, model.rotation);
  model.nodal_force = detail::nodal_forces(model.scene, model.mesh, point_nodes);
  if (!scene.steps.empty()) model.load_shares = detail::load_shares(model, point_nodes);
  if (free_motions.cols() > 0) model.free_modes = detail::free_modes_on_dofs(model, free_motions);

  detail::warn_near_incompressible(scene, model.mesh, model.warnings);
  model.timings.add("model", clock.seconds());
  return model;
}

}  // namespace contactqp
