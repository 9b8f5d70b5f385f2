// Assembly of K and f over the free DOFs, and of the contact rows.
#include <Eigen/SparseCore>
#include <cmath>
#include <limits>

#include "contact/contact.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/model.hpp"
#include "model/coarse_space.hpp"
#include "model/rigid_body_modes.hpp"
#include "stiffness_matrix.hpp"

namespace contactqp {
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

// Units so far from one that K or f leave double precision are bad input, named as the scene
// wrote it: beyond the largest double they overflow to Inf; below DBL_MIN/DBL_EPSILON the
// entries within round-off of the largest are subnormal and lose digits (E = 1e-320 gave
// "converged" with P = 0).
void refuse_unrepresentable(const Model& model, const QuadraticProgram& qp) {
  const Eigen::Map<const Eigen::VectorXd> k_values(qp.K.valuePtr(), qp.K.nonZeros());
  detail::refuse_unrepresentable(model, k_values.size() ? k_values.cwiseAbs().maxCoeff() : 1.0, k_values.allFinite(),
                                 qp.f.size() ? qp.f.cwiseAbs().maxCoeff() : 0.0, qp.f.allFinite());
}

}  // namespace

namespace detail {
void refuse_unrepresentable(const Model& model, double largest_k, bool k_finite, double largest_f, bool f_finite) {
  constexpr double kSmallest = std::numeric_limits<double>::min() / std::numeric_limits<double>::epsilon();
  const double thickness = model.scene.body.thickness;
  const std::string stiffness =
      "= " + detail::format_value(model.scene.material.E) +
      (thickness != 1 ? " (body.thickness = " + detail::format_value(thickness) + ")" : std::string());
  if (!k_finite)
    throw InputError("material.E", stiffness + ": the stiffness matrix overflows double precision; use other units");
  if (largest_k < kSmallest)
    throw InputError("material.E", stiffness + ": the stiffness matrix underflows double precision; use other units");
  if (!f_finite)
    throw InputError("load",
                     "gives a load vector that overflows double precision (forces or prescribed displacements "
                     "too large for these units); use other units");
  if (largest_f > 0 && largest_f < kSmallest)
    throw InputError("load",
                     "gives a load vector that underflows double precision (forces or prescribed displacements "
                     "too small for these units); use other units");
}

Eigen::MatrixXd dof_frame_rotated(const Model& model, const int* v, int npe, Eigen::MatrixXd Ke) {
  rotate_to_dof_frames(model, v, npe, Ke);
  return Ke;
}
}  // namespace detail

QuadraticProgram assemble_qp(Model& model, const std::vector<char>& elements) {
  Stopwatch clock;
  const Mesh& mesh = model.mesh;
  const int dim = mesh.dim;
  if (!elements.empty() && static_cast<int>(elements.size()) != mesh.n_elements())
    throw InputError("elements", "has " + std::to_string(elements.size()) + " entries for " +
                                     std::to_string(mesh.n_elements()) + " elements");

  QuadraticProgram qp;
  qp.f = Eigen::VectorXd::Zero(model.n_free);
  detail::assemble_stiffness(model, elements, qp.K, qp.f);
  // Force loads: f_a = Tᵀ f_x at each node (T its DOF frame); forces at prescribed DOFs go
  // to the reactions.
  for (int node = 0; node < mesh.n_nodes(); ++node) {
    Eigen::VectorXd force = model.nodal_force.segment(dim * node, dim);
    if (!model.frame_of_node.empty() && model.frame_of_node[node] >= 0)
      force = dof_frame(model, node).transpose() * force;
    for (int c = 0; c < dim; ++c)
      if (model.free_index[dim * node + c] >= 0) qp.f[model.free_index[dim * node + c]] += force[c];
  }
  refuse_unrepresentable(model, qp);
  detail::add_contact_rows(model, qp);
  qp.near_null_space = detail::rigid_body_modes(model);  // for AMG in an iterative solver of K
  qp.coarse_space = detail::p1_coarse_space(model);      // for its P1 level (quadratic elements)
  model.timings.add("assemble", clock.seconds());
  return qp;
}

Eigen::VectorXd full_displacement(const Model& model, const Eigen::VectorXd& u) {
  Eigen::VectorXd full = model.prescribed;
  for (size_t dof = 0; dof < model.free_index.size(); ++dof)
    if (model.free_index[dof] >= 0) full[dof] = u[model.free_index[dof]];
  const int dim = model.dim;
  if (!model.frame_of_node.empty())
    for (int node = 0; node < model.mesh.n_nodes(); ++node)
      if (model.frame_of_node[node] >= 0)
        full.segment(dim * node, dim) = dof_frame(model, node) * full.segment(dim * node, dim);
  return full;
}

}  // namespace contactqp
