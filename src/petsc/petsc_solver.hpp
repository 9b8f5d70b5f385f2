// The PETSc solver of K, seen from the rest of the room: no PETSc header here. Built from
// petsc_solver.cpp (which registers it as the solver of LinearSolverKind::Petsc); absent
// without PETSc, when nothing registers that kind.
#pragma once

#include <memory>
#include <vector>

#include "contactqp/linear_solver.hpp"

namespace contactqp::detail {

// Where the matrix's rows are: every rank holds the whole matrix (the default), or its share
// of it (ParQuadraticProgram: the ranks' shares sum to the matrix); and the row of each unknown
// in the distributed matrix (empty: their own order).
struct MatrixLayout {
  bool share = false;
  std::vector<int> distributed_row;
};

// A KSP on a PETSc copy of A (docs/linear-solvers.md), with PETSc's options from
// options.library_options["petsc"]. Throws InputError when the PETSc options are bad input
// that PETSc reports before any work; numerical failures go to ok().
std::shared_ptr<const LinearSolver> make_petsc_solver(const Eigen::SparseMatrix<double>& A,
                                                      const LinearSolverOptions& options,
                                                      const MatrixLayout& layout = {});

}  // namespace contactqp::detail
