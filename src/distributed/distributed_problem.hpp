// The contact QP of a distributed model in the petsc backend's bound form (docs/petsc-design.md):
// with v = T u_C at each candidate node (bound_transform.hpp) and u = Q v, row i of B u ≤ g is
// the bound v_i ≤ g_i, and the problem is
//
//     minimise ½ vᵀ A v − bᵀ v   subject to   v_i ≤ g_i,     A = QᵀKQ, b = Qᵀf.
//
// Since Q is per node, A = Σ_e Q_eᵀ K_e Q_e: every rank transforms its own elements' matrices
// and adds them straight into PETSc's distributed A. K is never assembled, in Eigen or
// anywhere; each rank holds only its rows of A, b and f and its own bounds.
#pragma once

#include <petscmat.h>

#include <Eigen/Core>
#include <vector>

#include "distributed_model.hpp"

namespace contactqp::detail {

// The change of variables at one candidate node: its rows' coefficients on its columns.
struct NodeTransform {
  int node = -1;
  int first_candidate = 0, n_rows = 0;  // its rows: local.candidates[first_candidate …]
  std::vector<int> columns;             // local free DOFs (ascending) where its rows are nonzero
  Eigen::MatrixXd T, Q;                 // v_C = T u_C, u_C = Q v_C
};

struct DistributedBoundQp {
  // Rows: every node with a free DOF, dim each (DistributedModel::first_row …), v-variables;
  // SPD. A prescribed DOF's row and column hold only its diagonal K_pp, and b_p = 0, so v_p = 0.
  Mat A = nullptr;
  int block_size = 1;  // dim: A's block size, a node's rows together
  Vec b = nullptr;     // Qᵀ f, A's layout
  Vec f = nullptr;     // f itself (u-variables), for the certificate
  // This rank's bounds, one per own candidate in candidate order: the global row of its
  // variable, and g_i.
  std::vector<PetscInt> bounded;
  std::vector<double> upper;
  std::vector<Vec> near_null_space;  // rigid-body modes in v (3 in 2D, 6 in 3D), 0 at prescribed rows, orthonormal
  // Quadratic elements (null otherwise): the P2 → P1 nodal interpolation in v, P_v = T P_u,
  // P_u = (1 at a vertex, ½ ½ from a mid-edge node's two edge ends) ⊗ I_dim, A's rows (the
  // prescribed ones zero) by the dim components of every vertex node (dim·vertex + c, with
  // the vertex's owner), a candidate vertex's columns in its own variables (P_v = T P_u Q_c:
  // its group's T on them too, as bound_form.cpp does); the rigid-body modes on that level (0
  // at prescribed vertex DOFs, not orthonormalised); and per own bound the coarse column of its
  // variable when its node is a vertex, −1 otherwise (the P1 start's bounds).
  Mat coarse_interpolation = nullptr;
  std::vector<Vec> coarse_near_null_space;
  std::vector<PetscInt> coarse_bounded;
  std::vector<int> vertex_of_node;  // each local node's number among the vertices (P's columns), −1 off them
  // The transforms of the candidate nodes this rank holds (its own and its ghosts'), and of
  // each local node the index of its transform or −1.
  std::vector<NodeTransform> transforms;
  std::vector<int> transform_of_node;

  DistributedBoundQp() = default;
  DistributedBoundQp(DistributedBoundQp&& other) noexcept;
  DistributedBoundQp& operator=(DistributedBoundQp&& other) noexcept;
  DistributedBoundQp(const DistributedBoundQp&) = delete;
  DistributedBoundQp& operator=(const DistributedBoundQp&) = delete;
  ~DistributedBoundQp();
};

// Collective. InputError (on every rank) when a node's rows are linearly dependent, or K or f
// leave double precision (the serial assemble_qp's checks).
DistributedBoundQp assemble_distributed_bound_qp(const DistributedModel& model);

// f, b = Qᵀ f and the bounds g for the model's loads as they stand (local.prescribed and
// local.nodal_force): at assembly, and again at each load step once set_step_loads() has set
// them — A, its hierarchy and the bounded rows stay. Collective; f's largest magnitude over the
// ranks and whether it is finite, for refuse_unrepresentable().
struct LoadVectorRange {
  double largest = 0;
  bool finite = true;
};
LoadVectorRange set_load_vectors(const DistributedModel& model, DistributedBoundQp& qp);

}  // namespace contactqp::detail
