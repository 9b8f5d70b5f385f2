// The contact QP of a run on several processes (mpirun), held in parts: the PETSc room's
// distributed problem (library cqp_petsc, src/petsc/; docs/petsc-design.md, "mpirun"). The generic
// QuadraticProgram, SolveOptions and certificate know nothing of processes; this type carries
// what they leave out, and its functions run the generic steps with the sums over the ranks.
//
// Today each rank holds a share of K (the elements it owns; the shares sum to K) and f, B, g,
// the rows and the near-null space whole. The seam between the solver and the distributed
// data (docs/petsc-design.md, "The room"): a solver reads only this type, so the data may move to
// rank-local rows (with a global DOF numbering) without touching the solver's interface.
#pragma once

#include <string>
#include <vector>

#include "contactqp/certificate.hpp"
#include "contactqp/model.hpp"
#include "contactqp/qp.hpp"

namespace contactqp {

// Which rank this process is, and in which rows of the distributed matrix the DOFs go.
struct RankShare {
  int rank = 0;
  int ranks = 1;
  // The DOFs' rows to use (a permutation, as ParQuadraticProgram::distributed_row), or empty to
  // partition the mesh now. PT-Scotch's partition differs from call to call in one process, so
  // shares meant to sum to one K must be given the rows the first of them chose.
  std::vector<int> distributed_row;
};

struct ParQuadraticProgram {
  // K: this rank's share (the elements whose first free DOF's row lies in its block of rows,
  // PETSc's split of the rows into contiguous blocks); the shares over the ranks sum to the
  // problem's K. f, B, g, rows, near_null_space and friction: whole on every rank.
  QuadraticProgram share;
  int rank = 0;   // this process's rank
  int ranks = 1;  // the ranks holding a share
  // The row of each DOF in the distributed matrix: the DOFs of part 0 of a partition of the
  // mesh's node graph first, then part 1's, ..., so that each rank's block of rows is a compact
  // piece of the body. Empty: the DOFs' own order.
  std::vector<int> distributed_row;

  int n_dofs() const { return share.n_dofs(); }
  int n_constraints() const { return share.n_constraints(); }
};

// Assembles this rank's share (collective when the mesh is partitioned here: every rank calls
// it). With share.ranks == 1 the share is the whole K.
ParQuadraticProgram assemble_par_qp(Model& model, const RankShare& share);

// K u for a u whole on every rank: the ranks' products summed (collective).
VectorXd K_times(const ParQuadraticProgram& qp, const VectorXd& u);

// solve() for a problem held in shares: the same validation, scaling and guards, the petsc
// backend on the distributed matrix (any other backend is bad input: it needs K whole).
// Collective; u and λ whole on every rank.
SolveResult solve(const ParQuadraticProgram& qp, const SolveOptions& options);

// certify() for it: the same formulas (certificate.hpp's certificate_terms() and
// certificate_from(), or with friction certify_given_Ku()) with K u summed over the ranks; θ
// needs K_factor (the petsc backend's result carries one), else it is not available. λ_T:
// m · n_directions entries with friction (empty reads as 0).
Certificate certify(const ParQuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda,
                    const LinearSolver* K_factor);
Certificate certify(const ParQuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda, const VectorXd& lambda_t,
                    const LinearSolver* K_factor);

// Splits a graph (vertex v's neighbours are neighbours[offsets[v]] .. neighbours[offsets[v + 1] − 1])
// into `parts` parts of nearly equal size with few edges between them: PETSc's MatPartitioning
// with PT-Scotch (-mat_partitioning_type in `petsc_options` or PETSC_OPTIONS chooses another).
// part[v] for every vertex, the same on every rank. Collective under mpirun; starts PETSc. All
// zeros for one part or without PETSc; empty if PETSc failed.
std::vector<int> partition_graph(const std::vector<long>& offsets, const std::vector<int>& neighbours, int parts,
                                 const std::string& petsc_options = "");

// Where SolveOptions keeps PETSc's options database entries ("-ksp_type minres -pc_type hypre":
// library_options["petsc"], from --petsc-options or a scene's solver.petsc_options).
std::string petsc_options_of(const SolveOptions& options);
void set_petsc_options(SolveOptions& options, const std::string& entries);

}  // namespace contactqp
