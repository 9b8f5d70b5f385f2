// Prescribed displacements (the displacement loads and the symmetry plane) as eliminated DOFs,
// and the rigid surfaces of force loads as one shared DOF per surface and component.
#include <algorithm>
#include <cmath>

#include "contactqp/errors.hpp"
#include "model_parts.hpp"

namespace contactqp::detail {
namespace {

// Prescribes DOF `dof` to `value`; a second, different value for the same DOF is an error.
void prescribe(Model& model, int dof, double value, const std::string& field) {
  if (model.free_index[dof] == -1 && model.prescribed[dof] != value) {
    const double scale = std::max(std::abs(value), std::abs(model.prescribed[dof]));
    if (std::abs(model.prescribed[dof] - value) > 1e-12 * scale)
      throw InputError(field, "= " + format_value(value) + " conflicts with " + format_value(model.prescribed[dof]) +
                                  " prescribed at node " + std::to_string(dof / model.dim) + " by another condition");
  }
  model.free_index[dof] = -1;
  model.prescribed[dof] = value;
}

// The rigid surfaces of the force loads (model.rigid_surfaces, their columns still −1): of each
// DOF the surface that ties it, −1 for none. A tied DOF must be free: one that another condition
// prescribes, or another surface ties, is an InputError naming the force's value.
std::vector<int> tie_rigid_surfaces(Model& model, const Scene& scene, const NodesOfBoundary& nodes_of) {
  const int dim = model.dim;
  std::vector<int> surface_of_dof(model.free_index.size(), -1);
  model.rigid_surfaces.clear();
  for (size_t l = 0; l < scene.loads.size(); ++l) {
    const RigidForceLoad* load = scene.loads[l].as<RigidForceLoad>();
    if (!load) continue;
    std::vector<int> nodes = nodes_of(load->boundary);
    std::sort(nodes.begin(), nodes.end());
    if (nodes.empty())
      throw InputError(scene.loads[l].path + ".boundary",
                       "= \"" + load->boundary + "\": has no nodes to carry the force");
    for (int c = 0; c < dim; ++c) {
      if (!load->value[c]) continue;
      const std::string field = scene.loads[l].path + ".value[" + std::to_string(c) + "]";
      const int index = static_cast<int>(model.rigid_surfaces.size());
      for (int node : nodes) {
        const int dof = dim * node + c;
        const std::string where = "ties \"" + load->boundary + "\" along " + "xyz"[c] +
                                  " as one rigid surface, but node " + std::to_string(node) + " there is ";
        if (model.free_index[dof] == -1)
          throw InputError(field, "= " + format_value(*load->value[c]) + " " + where + "prescribed (to " +
                                      format_value(model.prescribed[dof]) +
                                      ") by another condition; give null for this component");
        if (surface_of_dof[dof] >= 0)
          throw InputError(field, "= " + format_value(*load->value[c]) + " " + where +
                                      "on another rigid surface along " + "xyz"[c] + " too");
        surface_of_dof[dof] = index;
      }
      RigidSurface surface;
      surface.load = static_cast<int>(l);
      surface.component = c;
      surface.force = *load->value[c];
      surface.nodes = nodes;
      model.rigid_surfaces.push_back(std::move(surface));
    }
  }
  return surface_of_dof;
}

}  // namespace

void apply_displacement_conditions(Model& model, const Scene& scene, const Eigen::Matrix3d& rotation) {
  apply_displacement_conditions(model, scene, rotation,
                                [&model](const std::string& name) { return boundary_nodes(model.mesh, name); });
}

void apply_displacement_conditions(Model& model, const Scene& scene, const Eigen::Matrix3d& rotation,
                                   const NodesOfBoundary& nodes_of) {
  const int n_nodes = model.mesh.n_nodes();
  const int dim = model.mesh.dim;
  model.dim = dim;
  model.free_index.assign(dim * n_nodes, 0);
  model.prescribed = Eigen::VectorXd::Zero(dim * n_nodes);
  for (const LoadSpec& load : scene.loads) {
    const DisplacementLoad* d = load.as<DisplacementLoad>();
    if (!d) continue;
    for (int node : nodes_of(d->boundary))
      for (int c = 0; c < dim; ++c)
        if (d->value[c]) prescribe(model, dim * node + c, *d->value[c], load.path + ".value");
  }
  for (const std::string& plane : symmetry_boundaries(scene.body, dim))
    for (int node : nodes_of(plane)) prescribe(model, dim * node + symmetry_component(plane), 0.0, "body.symmetry");
  const std::vector<int> surface_of_dof = tie_rigid_surfaces(model, scene, nodes_of);
  // Free DOFs in DOF order; a rigid surface's DOFs all take the column its first one gets.
  model.n_free = 0;
  for (size_t dof = 0; dof < model.free_index.size(); ++dof) {
    int& index = model.free_index[dof];
    if (index != 0) {
      index = -1;
    } else if (surface_of_dof[dof] < 0) {
      index = model.n_free++;
    } else {
      RigidSurface& surface = model.rigid_surfaces[static_cast<size_t>(surface_of_dof[dof])];
      if (surface.column < 0) surface.column = model.n_free++;
      index = surface.column;
    }
  }

  // Prescribed components are along the scene's own axes: in a rotated scene, the nodes that
  // carry one get the rotated axes as their DOF frame (a skew boundary condition).
  model.frames.clear();
  model.frame_of_node.clear();
  if (rotation != Eigen::Matrix3d::Identity()) {
    model.frames.push_back(rotation.topLeftCorner(dim, dim));
    model.frame_of_node.assign(n_nodes, -1);
    for (int node = 0; node < n_nodes; ++node)
      for (int c = 0; c < dim; ++c)
        if (model.free_index[dim * node + c] < 0 || surface_of_dof[dim * node + c] >= 0) model.frame_of_node[node] = 0;
  }
  turn_rigid_surfaces(model, scene, rotation, nodes_of);
}

double rigid_surface_share(const Model& model, const RigidSurface& surface) {
  const BodySpec& body =
      model.bodies.empty() ? model.scene.body : model.bodies[model.body_of_node(surface.nodes.front())].scene.body;
  return surface.force / symmetry_copies(body, model.dim);
}

Eigen::VectorXd rigid_surface_forces(const Model& model) {
  Eigen::VectorXd forces = Eigen::VectorXd::Zero(model.dim * model.mesh.n_nodes());
  for (const RigidSurface& surface : model.rigid_surfaces)
    forces[model.dim * surface.nodes.front() + surface.component] += rigid_surface_share(model, surface);
  return forces;
}

}  // namespace contactqp::detail
