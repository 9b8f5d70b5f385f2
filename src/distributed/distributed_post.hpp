// Post-processing of a distributed solution (docs/petsc-design.md, "Distributed runs"), the same
// numbers as one process gets:
// - the contact summary and the Hertz and Boussinesq comparisons on rank 0, from the contact
//   rows gathered there (a surface's worth: the candidates, and the contact boundary's faces at
//   them), by the serial code on a model of that surface;
// - the support reactions as sums of each rank's elements and rows (MPI_Allreduce);
// - the ParaView arrays of each rank's nodes, nodal averages and contact fields added up or
//   taken from the node's owner, for its piece of the .pvtu.
#pragma once

#include <memory>
#include <vector>

#include "contactqp/io.hpp"
#include "contactqp/post.hpp"
#include "distributed_certificate.hpp"

namespace contactqp::detail {

// The free DOFs of all of this rank's nodes (its own from `solution`, the others' from their
// owners), as model.local numbers them. Collective.
Eigen::VectorXd local_free_values(const DistributedModel& model, const Eigen::VectorXd& own);

// The rows gathered on rank 0: a model of the contact surface (the scene, the candidates' nodes
// and the contact boundary's faces at them, the candidates in the global row order), a QP with
// as many rows (its K empty), and every row's λ. Collective; other ranks get empty ones.
struct ContactSurface {
  std::shared_ptr<Model> model;
  std::shared_ptr<QuadraticProgram> qp;
  Eigen::VectorXd lambda;
};
ContactSurface gather_contact_surface(const DistributedModel& model, const Eigen::VectorXd& own_lambda);

// The contact summary on rank 0 (the others' is empty) with the whole body's count of
// penetrating nodes outside the candidate set; the nodal pressure of each own row (pressures
// are computed on rank 0, where the neighbours of every row are). Collective.
ContactSummary distributed_contact_summary(const DistributedModel& model, const ContactSurface& surface,
                                           const Eigen::VectorXd& displacement, std::vector<double>& own_pressure);

// g − B u of every contact row this rank holds (local.candidates; all of its nodes' free DOFs
// are in `local_u`, local_free_values()).
Eigen::VectorXd row_slacks(const Model& local, const Eigen::VectorXd& local_u);

// The reactions of the displacement loads, on every rank. Collective.
std::vector<Reaction> distributed_reactions(const DistributedModel& model, const Eigen::VectorXd& local_u,
                                            const Eigen::VectorXd& own_lambda);

// This rank's piece of the ParaView file: the arrays of vtu_document() at its nodes. Collective.
struct PieceArrays {
  int dim = 3;
  Eigen::VectorXd displacement;
  NodalStress stress;
  ContactFields contact;
  std::vector<PointArray> arrays() const;
};
PieceArrays piece_arrays(const DistributedModel& model, const Eigen::VectorXd& displacement,
                         const Eigen::VectorXd& local_u, const Eigen::VectorXd& own_lambda,
                         const std::vector<double>& own_pressure);

// Writes this rank's piece beside `pvtu_path` (STEM_RANK.vtu) and, on rank 0, the .pvtu:
// all pieces appear, and then the .pvtu, or none of them (every rank removes its piece when one
// failed). Collective. On one process a path not ending in .pvtu gets the one piece itself: a
// whole .vtu, as the one-process path writes it.
// `cell_arrays` at this rank's elements (error_indicator).
void write_pvtu(const std::string& pvtu_path, const Mesh& mesh, const std::vector<PointArray>& arrays,
                const std::vector<PointArray>& cell_arrays = {});

}  // namespace contactqp::detail
