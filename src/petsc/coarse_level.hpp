// The P1 level of quadratic elements (contactqp/coarse_space.hpp) as PETSc objects: the
// interpolation P from the level's columns to A's rows, and the rigid-body modes on the level,
// for set_up_multigrid() (multigrid.hpp). Used by the PETSc solver of K and the petsc backend.
#pragma once

#include <petscmat.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "petsc_matrix.hpp"

namespace contactqp::detail {

// The level in the caller's variables: P (n × n_coarse, rows in the variables of A), the modes
// on the level (n_coarse × k, or empty), and per column its vertex (a vertex's columns are
// consecutive); `vertex_row` per column the variable of A that the column's vertex itself
// carries (a row with weight 1), or −1.
struct CoarseLevelInput {
  const Eigen::SparseMatrix<double>* interpolation = nullptr;
  const Eigen::MatrixXd* modes = nullptr;
  const std::vector<int>* column_vertex = nullptr;
  const std::vector<int>* vertex_row = nullptr;
  int block_size = 1;
};

class CoarseLevel {
 public:
  CoarseLevel() = default;
  CoarseLevel(const CoarseLevel&) = delete;
  CoarseLevel& operator=(const CoarseLevel&) = delete;
  ~CoarseLevel();

  // Builds P with A's row layout (rows [first, end) on this rank, in `order`) and columns
  // owned vertex by vertex by the rank that owns the vertex's own rows, so that the Galerkin
  // product PᵀAP stays mostly local; the column block size is `block_size` when every vertex
  // has that many columns; of A's matrix type (MatPtAP needs the two alike). Collective; every
  // rank passes the whole input.
  PetscErrorCode create(const CoarseLevelInput& input, const RowOrder& order, PetscInt first, PetscInt end, Mat A);

  Mat interpolation() const { return P_; }
  MatNullSpace modes() const { return modes_; }
  // The PETSc column of the input's column c.
  PetscInt column(int c) const { return column_[c]; }

 private:
  Mat P_ = nullptr;
  MatNullSpace modes_ = nullptr;
  std::vector<PetscInt> column_;
};

}  // namespace contactqp::detail
