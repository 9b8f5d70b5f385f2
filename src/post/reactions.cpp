// Support reactions: what the prescribed displacements push with.
#include <algorithm>
#include <cmath>

#include "contact/contact.hpp"
#include "contactqp/post.hpp"

namespace contactqp {
namespace {

// The force loads' rigid surfaces: the force each carries (the load at this step) and how far
// it moved, one entry per load, after the supports.
std::vector<Reaction> rigid_surface_reactions(const Model& model, const Eigen::VectorXd& u) {
  std::vector<Reaction> out;
  for (size_t l = 0; l < model.scene.loads.size(); ++l) {
    const RigidForceLoad* load = model.scene.loads[l].as<RigidForceLoad>();
    if (!load) continue;
    Reaction entry;
    entry.load = model.scene.loads[l].path;
    entry.boundary = load->boundary;
    Eigen::Vector3d along_axes = Eigen::Vector3d::Zero();  // the scene's own axes
    for (const RigidSurface& surface : model.rigid_surfaces) {
      if (surface.load != static_cast<int>(l)) continue;
      along_axes[surface.component] = surface.force;
      if (surface.column < u.size()) entry.displacement[surface.component] = u[surface.column];
    }
    entry.force = model.rotation * along_axes;
    if (model.dim == 2) entry.force.z() = 0;
    for (const RigidRotation& turn : model.rigid_rotations) {
      if (turn.load != static_cast<int>(l)) continue;
      entry.moment[turn.axis] = turn.moment;
      entry.about = model.rotation.transpose() * turn.centre;
      for (int k = 0; k < 3; ++k)  // turned there and back: round-off, not a place
        if (std::abs(entry.about[k]) <= 1e-12 * entry.about.norm()) entry.about[k] = 0;
      if (turn.column < u.size()) entry.rotation[turn.axis] = u[turn.column];
    }
    out.push_back(entry);
  }
  return out;
}

}  // namespace

std::vector<Reaction> reactions(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& u,
                                const Eigen::VectorXd& lambda, const Eigen::VectorXd& lambda_t) {
  // λ: one row per candidate, in candidate order; λ_T through the QP's friction block.
  const Eigen::VectorXd friction = lambda_t.size() > 0 ? friction_nodal_forces(model, qp, lambda_t) : Eigen::VectorXd();
  return reactions(
      model, u, lambda, [&model](const std::string& name) { return boundary_nodes(model.mesh, name); }, friction);
}

std::vector<Reaction> reactions(const Model& model, const Eigen::VectorXd& u, const Eigen::VectorXd& lambda,
                                const std::function<std::vector<int>(const std::string&)>& nodes_of,
                                const Eigen::VectorXd& friction_forces) {
  const Mesh& mesh = model.mesh;
  // Only the nodes of prescribed boundaries need their residual, so only the elements at them
  // are visited, in element order: each node's sum is the one a loop over all elements makes.
  std::vector<char> prescribed(mesh.n_nodes(), 0);
  bool any = false;
  for (const LoadSpec& load : model.scene.loads)
    if (const DisplacementLoad* d = load.as<DisplacementLoad>()) {
      for (int node : nodes_of(d->boundary)) prescribed[node] = 1;
      any = true;
    }
  if (!any) return rigid_surface_reactions(model, u);
  const Eigen::VectorXd displacement = full_displacement(model, u);
  const std::vector<ElementLaw> laws = element_laws(model);
  const int npe = mesh.nodes_per_element();
  const int dim = model.dim;
  // Internal forces K u in the global axes, element by element (K of the prescribed DOFs too).
  Eigen::VectorXd residual = -model.nodal_force;
  std::vector<Eigen::Vector3d> x(npe);
  Eigen::VectorXd ue(dim * npe);
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    if (std::none_of(v, v + npe, [&prescribed](int node) { return prescribed[node]; })) continue;
    for (int i = 0; i < npe; ++i) {
      x[i] = mesh.nodes[v[i]];
      ue.segment(dim * i, dim) = displacement.segment(dim * v[i], dim);
    }
    const Eigen::VectorXd fe =
        element_stiffness(mesh.type(), x.data(), laws[body_of_element(model, e)], model.scene.body.thickness) * ue;
    for (int i = 0; i < npe; ++i) residual.segment(dim * v[i], dim) += fe.segment(dim * i, dim);
  }
  // The obstacles push node i with λ n (a pair's row also its face nodes with −λ N_j n): what
  // remains is the support's push.
  for (int i = 0; i < lambda.size(); ++i) {
    const Candidate& c = model.candidates[i];
    if (c.pair >= 0) {
      residual.segment(dim * c.node, dim) -= lambda[i] * c.normal.head(dim);
      for (int j = 0; j < c.n_face_nodes; ++j)
        residual.segment(dim * c.face_nodes[j], dim) += lambda[i] * c.weights[j] * c.normal.head(dim);
      continue;
    }
    const Eigen::Vector3d n = detail::project(model.scene.obstacles[c.obstacle], mesh.nodes[c.node]).normal;
    residual.segment(dim * c.node, dim) -= lambda[i] * n.head(dim);
  }
  if (friction_forces.size() > 0) residual -= friction_forces;
  std::vector<Reaction> out;
  for (const LoadSpec& load : model.scene.loads) {
    const DisplacementLoad* d = load.as<DisplacementLoad>();
    if (!d) continue;
    Reaction reaction;
    reaction.load = load.path;
    reaction.boundary = d->boundary;
    for (int node : nodes_of(d->boundary)) reaction.force.head(dim) += residual.segment(dim * node, dim);
    // With symmetry the mirrored parts push the same along the cuts and cancel across them.
    reaction.force = whole_body_sum(model, reaction.force);
    out.push_back(reaction);
  }
  for (Reaction& surface : rigid_surface_reactions(model, u)) out.push_back(std::move(surface));
  return out;
}

}  // namespace contactqp
