// Assembly of K and f over the free DOFs, and of the contact rows.
#include <Eigen/SparseCore>
#include <cmath>
#include <limits>

#include "contact/contact.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/model.hpp"
#include "fe/stiffness_matrix.hpp"
#include "model/coarse_space.hpp"
#include "model/model_parts.hpp"
#include "model/rigid_body_modes.hpp"

namespace contactqp {
namespace {

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
// Force loads: f_a = Tᵀ f_x at each node (T its DOF frame); forces at prescribed DOFs go
// to the reactions.
void add_force_loads(const Model& model, Eigen::VectorXd& f) {
  const int dim = model.dim;
  for (int node = 0; node < model.mesh.n_nodes(); ++node) {
    Eigen::VectorXd force = model.nodal_force.segment(dim * node, dim);
    if (!model.frame_of_node.empty() && model.frame_of_node[node] >= 0)
      force = dof_frame(model, node).transpose() * force;
    for (int c = 0; c < dim; ++c)
      for_each_column(model, dim * node + c, [&](int column, double w) { f[column] += w * force[c]; });
  }
  // A rigid surface's force acts on its one column (Tᵀf: the sum over its nodes is the force),
  // a turning one's moment on its angle's (symmetry planes refuse a moment: no share to take).
  for (const RigidSurface& surface : model.rigid_surfaces) f[surface.column] += rigid_surface_share(model, surface);
  for (const RigidRotation& turn : model.rigid_rotations) f[turn.column] += turn.moment;
}

void refuse_unrepresentable(const Model& model, double largest_k, bool k_finite, double largest_f, bool f_finite) {
  constexpr double kSmallest = std::numeric_limits<double>::min() / std::numeric_limits<double>::epsilon();
  const double thickness = model.scene.body.thickness;
  const std::string stiffness =
      "= " + format_value(model.scene.material.E) +
      (thickness != 1 ? " (body.thickness = " + format_value(thickness) + ")" : std::string());
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

void set_step_loads(Model& model, const std::vector<double>& factors, const std::string& step) {
  const int n = static_cast<int>(model.prescribed.size());
  Eigen::VectorXd prescribed = Eigen::VectorXd::Zero(n), nodal_force = Eigen::VectorXd::Zero(n);
  std::vector<int> prescribed_by(n, -1);  // the load that set each DOF
  for (size_t l = 0; l < model.load_shares.size(); ++l) {
    const LoadShare& share = model.load_shares[l];
    nodal_force += factors[l] * share.nodal_force;
    for (const auto& [dof, value] : share.prescribed) {
      const double scaled = factors[l] * value;
      const int other = prescribed_by[dof];
      // The node by its place (a distributed run's part numbers its nodes its own way).
      if (other >= 0 &&
          std::abs(prescribed[dof] - scaled) > 1e-12 * std::max(std::abs(scaled), std::abs(prescribed[dof])))
        throw InputError(step, "prescribes the node at " + format_point(model.mesh.nodes[dof / model.dim], model.dim) +
                                   " by " + model.scene.loads[other].path + " and by " + model.scene.loads[l].path +
                                   " to different values (" + format_value(prescribed[dof]) + " and " +
                                   format_value(scaled) + "): scale them alike");
      prescribed[dof] = scaled;
      prescribed_by[dof] = static_cast<int>(l);
    }
  }
  model.prescribed = prescribed;
  model.nodal_force = nodal_force;
  for (RigidSurface& surface : model.rigid_surfaces)
    surface.force =
        factors[surface.load] * *model.scene.loads[surface.load].as<RigidForceLoad>()->value[surface.component];
  for (RigidRotation& turn : model.rigid_rotations)
    turn.moment = factors[turn.load] * *model.scene.loads[turn.load].as<RigidForceLoad>()->moment[turn.axis];
}

}  // namespace detail

QuadraticProgram assemble_qp(Model& model, const std::vector<char>& elements) {
  Stopwatch clock;
  const Mesh& mesh = model.mesh;
  if (!elements.empty() && static_cast<int>(elements.size()) != mesh.n_elements())
    throw InputError("elements", "has " + std::to_string(elements.size()) + " entries for " +
                                     std::to_string(mesh.n_elements()) + " elements");

  QuadraticProgram qp;
  qp.f = Eigen::VectorXd::Zero(model.n_free);
  detail::assemble_stiffness(model, elements, qp.K, qp.f);
  detail::add_force_loads(model, qp.f);
  refuse_unrepresentable(model, qp);
  detail::add_contact_rows(model, qp);
  detail::add_friction_rows(model, qp);                  // nothing without friction
  qp.near_null_space = detail::rigid_body_modes(model);  // for AMG in an iterative solver of K
  qp.null_space = model.free_modes;                      // a body only its contacts hold: its free motions
  qp.coarse_space = detail::p1_coarse_space(model);      // for its P1 level (quadratic elements)
  model.timings.add("assemble", clock.seconds());
  return qp;
}

void apply_load_step(Model& model, QuadraticProgram& qp, const std::vector<double>& factors, const std::string& step) {
  detail::set_step_loads(model, factors, step);
  qp.f = detail::prescribed_forces(model);
  detail::add_force_loads(model, qp.f);
  detail::add_contact_rows(model, qp);  // the same B; g with this step's prescribed values
}

Eigen::VectorXd full_displacement(const Model& model, const Eigen::VectorXd& u) {
  Eigen::VectorXd full = model.prescribed;
  for (size_t dof = 0; dof < model.free_index.size(); ++dof)
    if (model.free_index[dof] >= 0) full[dof] = u[model.free_index[dof]];
  for (const Lever& lever : model.levers) full[lever.dof] += lever.weight * u[lever.column];  // a turning surface
  const int dim = model.dim;
  if (!model.frame_of_node.empty())
    for (int node = 0; node < model.mesh.n_nodes(); ++node)
      if (model.frame_of_node[node] >= 0)
        full.segment(dim * node, dim) = dof_frame(model, node) * full.segment(dim * node, dim);
  return full;
}

}  // namespace contactqp
