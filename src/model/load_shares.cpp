// Each load's share of a load path (model.hpp's LoadShare): its nodal forces and the DOFs it
// prescribes, which set_step_loads (assembly.cpp) scales step by step.
#include "contactqp/mesh.hpp"
#include "model/model_parts.hpp"

namespace contactqp::detail {

std::vector<LoadShare> load_shares(const Model& model, const std::vector<int>& point_nodes) {
  return load_shares(
      model, [&model](const std::string& name) { return boundary_nodes(model.mesh, name); },
      [&model, &point_nodes](std::size_t l) {
        Scene one = model.scene;  // the load alone
        one.loads = {model.scene.loads[l]};
        return nodal_forces(one, model.mesh, {point_nodes[l]});
      });
}

std::vector<LoadShare> load_shares(const Model& model, const NodesOfBoundary& nodes_of,
                                   const std::function<Eigen::VectorXd(std::size_t load)>& nodal_force) {
  const int dim = model.mesh.dim;
  std::vector<LoadShare> shares;
  for (std::size_t l = 0; l < model.scene.loads.size(); ++l) {
    const LoadSpec& load = model.scene.loads[l];
    LoadShare share;
    share.nodal_force = nodal_force(l);
    if (const auto* d = load.as<DisplacementLoad>())
      for (int node : nodes_of(d->boundary))
        for (int c = 0; c < dim; ++c)
          if (d->value[c]) share.prescribed.emplace_back(dim * node + c, *d->value[c]);
    shares.push_back(std::move(share));
  }
  return shares;
}

}  // namespace contactqp::detail
