// Assembly of K and f over the free DOFs, and of the contact rows.
#include <Eigen/SparseCore>

#include "../contact/contact.hpp"
#include "contactqp/model.hpp"

namespace contactqp {

QuadraticProgram assemble_qp(Model& model) {
  Stopwatch clock;
  const Mesh& mesh = model.mesh;
  const Eigen::Matrix3d D = elasticity_matrix(model.scene.model, model.scene.material);
  const double thickness = model.scene.body.thickness;
  const int npe = mesh.nodes_per_element();

  QuadraticProgram qp;
  qp.f = Eigen::VectorXd::Zero(model.n_free);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<size_t>(mesh.n_elements()) * 4 * npe * npe);
  std::vector<Eigen::Vector2d> coordinates(npe);
  std::vector<int> dofs(2 * npe);
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    for (int i = 0; i < npe; ++i) {
      coordinates[i] = mesh.nodes[v[i]];
      dofs[2 * i] = 2 * v[i];
      dofs[2 * i + 1] = 2 * v[i] + 1;
    }
    const Eigen::MatrixXd Ke = element_stiffness(coordinates.data(), mesh.order, D, thickness);
    for (int i = 0; i < 2 * npe; ++i) {
      const int row = model.free_index[dofs[i]];
      if (row < 0) continue;
      for (int j = 0; j < 2 * npe; ++j) {
        const int column = model.free_index[dofs[j]];
        if (column >= 0)
          triplets.emplace_back(row, column, Ke(i, j));
        else
          qp.f[row] -= Ke(i, j) * model.prescribed[dofs[j]];  // prescribed displacement to the right-hand side
      }
    }
  }
  qp.K.resize(model.n_free, model.n_free);
  qp.K.setFromTriplets(triplets.begin(), triplets.end());
  qp.K.makeCompressed();
  triplets = {};
  detail::add_contact_rows(model, qp);
  model.timings.add("assemble", clock.seconds());
  return qp;
}

Eigen::VectorXd full_displacement(const Model& model, const Eigen::VectorXd& u) {
  Eigen::VectorXd full = model.prescribed;
  for (size_t dof = 0; dof < model.free_index.size(); ++dof)
    if (model.free_index[dof] >= 0) full[dof] = u[model.free_index[dof]];
  return full;
}

}  // namespace contactqp
