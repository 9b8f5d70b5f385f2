// The preconditioner of the PETSc solver of K and of the petsc backend's A: multigrid with a
// P1 level for quadratic elements (the P2 → P1 nodal interpolation as the first transfer, its
// Galerkin operator PᵀAP solved by GAMG), GAMG on A itself otherwise. docs/petsc-design.md ("The
// preconditioner") has the comparison behind the choice: on the 10-node spheres the P1 level
// makes the set-up 4–8 times cheaper than GAMG on A at fewer CG iterations, since the AMG then
// aggregates an eighth of the rows with a third of their nonzeros each.
#pragma once

#include <petscksp.h>

#include <string>

namespace contactqp::detail {

// What the problem offers the multigrid: PETSc objects the caller keeps (not owned here).
struct MultigridData {
  Mat A = nullptr;  // SPD; its block size (dim) and near-null space (rigid-body modes) set on it
  // Quadratic elements: P, A's rows × the P1 level's columns (dim per vertex), in A's variables;
  // null for linear elements.
  Mat coarse_interpolation = nullptr;
  MatNullSpace coarse_modes = nullptr;  // the rigid-body modes on the P1 level, or null
};

// The PETSc options every solver of A starts from (set_up_multigrid() puts them in the
// database for its set-up); the user's --petsc-options win. Smoothing by Chebyshev on Jacobi
// with CG eigenvalue estimates (PETSc's own advice for elasticity, src/snes/tutorials/ex56.c);
// GAMG (on A, or below the P1 level: prefix mg_coarse_) with the graph squared on its first two
// levels and at most 200 equations on the coarsest level (multigrid.cpp says why). These two
// are options, not PCGAMGSet...() calls: PETSc 3.18's PCSetFromOptions puts its own default
// back over PCGAMGSetAggressiveLevels() (measured: 4 levels instead of 3, the set-up 3× dearer).
extern const char* const kMultigridOptions[8][2];  // {name without "-" and prefix, value}

struct MultigridStatistics {
  std::string method;  // "mg: P1 level + gamg", "gamg", or the user's -pc_type
  int levels = 0;      // all levels, the P1 level and the AMG's below it included
  // Rows and nonzeros of all level operators over the finest's (PETSc's grid and operator
  // complexity); 0 for a preconditioner without levels (hypre, jacobi, ...).
  double grid_complexity = 0, operator_complexity = 0;
  double bytes = 0;             // level operators and interpolations on this rank (MatGetInfo)
  double galerkin_seconds = 0;  // the P1 Galerkin product PᵀAP
  double setup_seconds = 0;     // PCSetUp, the Galerkin product included
};

// Configures `pc`, whose operators are set (its Pmat is data.A), as the default multigrid —
// unless the options database names a -pc_type, which is then taken as it is — then
// PCSetFromOptions and PCSetUp. `coarse` receives PᵀAP when the P1 level is built (the caller
// destroys it after pc). Collective.
PetscErrorCode set_up_multigrid(PC pc, const MultigridData& data, Mat* coarse, MultigridStatistics* statistics);

// The levels, complexities and bytes of a set-up PC (PCMG, GAMG, ML, with a nested AMG on the
// coarsest level of a PCMG). Collective.
PetscErrorCode multigrid_statistics(PC pc, MultigridStatistics* statistics);

// The AMG on the P1 level of a PC built by set_up_multigrid, or pc itself when it has no P1
// level: the preconditioner of the P1 contact problem (bound_pdas.cpp's start).
PC p1_level_preconditioner(PC pc);

}  // namespace contactqp::detail
