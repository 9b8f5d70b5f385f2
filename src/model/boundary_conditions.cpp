// Prescribed displacements (the displacement loads and the symmetry plane) as eliminated DOFs.
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
  model.n_free = 0;
  for (int& index : model.free_index) index = index == 0 ? model.n_free++ : -1;

  // Prescribed components are along the scene's own axes: in a rotated scene, the nodes that
  // carry one get the rotated axes as their DOF frame (a skew boundary condition).
  model.frames.clear();
  model.frame_of_node.clear();
  if (rotation == Eigen::Matrix3d::Identity()) return;
  model.frames.push_back(rotation.topLeftCorner(dim, dim));
  model.frame_of_node.assign(n_nodes, -1);
  for (int node = 0; node < n_nodes; ++node)
    for (int c = 0; c < dim; ++c)
      if (model.free_index[dim * node + c] < 0) model.frame_of_node[node] = 0;
}

}  // namespace contactqp::detail
