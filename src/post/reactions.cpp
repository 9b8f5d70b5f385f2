// Support reactions: what the prescribed displacements push with.
#include "../contact/contact.hpp"
#include "contactqp/post.hpp"

namespace contactqp {

std::vector<Reaction> reactions(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& u,
                                const Eigen::VectorXd& lambda) {
  const Mesh& mesh = model.mesh;
  const Eigen::VectorXd displacement = full_displacement(model, u);
  const ElementLaw law = element_law(model.scene);
  const int npe = mesh.nodes_per_element();
  // Internal forces K u in global x, y, element by element (K of the prescribed DOFs too).
  Eigen::VectorXd residual = -model.nodal_force;
  std::vector<Eigen::Vector2d> x(npe);
  Eigen::VectorXd ue(2 * npe);
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    for (int i = 0; i < npe; ++i) {
      x[i] = mesh.nodes[v[i]];
      ue.segment<2>(2 * i) = displacement.segment<2>(2 * v[i]);
    }
    const Eigen::VectorXd fe = element_stiffness(x.data(), mesh.order, law, model.scene.body.thickness) * ue;
    for (int i = 0; i < npe; ++i) residual.segment<2>(2 * v[i]) += fe.segment<2>(2 * i);
  }
  // The obstacles push node i with λ n: what remains is the support's push.
  for (int i = 0; i < qp.n_constraints(); ++i) {
    const Candidate& c = model.candidates[i];
    residual.segment<2>(2 * c.node) -= lambda[i] * detail::project(model.scene.obstacles[c.obstacle], mesh.nodes[c.node]).normal;
  }
  const double mirror = model.scene.body.symmetry ? 2.0 : 1.0;
  std::vector<Reaction> out;
  for (const LoadSpec& load : model.scene.loads) {
    if (load.type != "displacement") continue;
    Reaction reaction{load.path, load.boundary, Eigen::Vector2d::Zero()};
    for (int node : boundary_nodes(mesh, load.boundary)) reaction.force += residual.segment<2>(2 * node);
    // With symmetry the mirrored half pushes the same vertically and opposite sideways.
    if (mirror == 2.0) {
      const Eigen::Vector2d axis = model.rotation.col(1);
      reaction.force = 2.0 * reaction.force.dot(axis) * axis;
    }
    out.push_back(reaction);
  }
  return out;
}

}  // namespace contactqp
