// The contact QP of a distributed model in the petsc backend's bound form (docs/petsc.md):
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
  Mat A = nullptr;  // rows: the free DOFs (DistributedModel::first_row …), v-variables; SPD
  Vec b = nullptr;  // Qᵀ f, A's layout
  Vec f = nullptr;  // f itself (u-variables), for the certificate
  // This rank's bounds, one per own candidate in candidate order: the global row of its
  // variable, and g_i.
  std::vector<PetscInt> bounded;
  std::vector<double> upper;
  std::vector<Vec> near_null_space;  // rigid-body modes in v (3 in 2D, 6 in 3D), orthonormal
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

}  // namespace contactqp::detail
