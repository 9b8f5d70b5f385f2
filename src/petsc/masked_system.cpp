// MaskedSystem (masked_system.hpp): the step's operator, right-hand side and preconditioner.
#include "masked_system.hpp"

#include "petsc_runtime.hpp"

namespace contactqp::detail {

MaskedSystem::~MaskedSystem() {
  if (petsc_finalized()) return;
  if (W_) MatDestroy(&W_);
  for (Vec* v : {&diagonal_, &multiply_work_, &apply_work_})
    if (*v) VecDestroy(v);
}

PetscErrorCode MaskedSystem::create(Mat A) {
  PetscFunctionBeginUser;
  A_ = A;
  PetscInt rows = 0, columns = 0, local_rows = 0, local_columns = 0;
  PetscCall(MatGetSize(A, &rows, &columns));
  PetscCall(MatGetLocalSize(A, &local_rows, &local_columns));
  PetscCall(MatCreateVecs(A, nullptr, &diagonal_));
  PetscCall(VecDuplicate(diagonal_, &multiply_work_));
  PetscCall(VecDuplicate(diagonal_, &apply_work_));
  PetscCall(MatGetDiagonal(A, diagonal_));
  PetscCall(MatCreateShell(PetscObjectComm(reinterpret_cast<PetscObject>(A)), local_rows, local_columns, rows, columns,
                           this, &W_));
  PetscCall(MatShellSetOperation(W_, MATOP_MULT, reinterpret_cast<void (*)(void)>(multiply)));
  PetscCall(MatShellSetOperation(W_, MATOP_GET_DIAGONAL, reinterpret_cast<void (*)(void)>(get_diagonal)));
  PetscCall(MatSetOption(W_, MAT_SPD, PETSC_TRUE));
  PetscFunctionReturn(0);
}

PetscErrorCode MaskedSystem::multiply(Mat W, Vec x, Vec y) {
  PetscFunctionBeginUser;
  MaskedSystem* self = nullptr;
  PetscCall(MatShellGetContext(W, &self));
  PetscCall(VecCopy(x, self->multiply_work_));
  PetscScalar* t = nullptr;
  PetscCall(VecGetArray(self->multiply_work_, &t));
  for (PetscInt i : self->fixed_) t[i] = 0;
  PetscCall(VecRestoreArray(self->multiply_work_, &t));
  PetscCall(MatMult(self->A_, self->multiply_work_, y));
  PetscScalar* out = nullptr;
  const PetscScalar *in = nullptr, *d = nullptr;
  PetscCall(VecGetArray(y, &out));
  PetscCall(VecGetArrayRead(x, &in));
  PetscCall(VecGetArrayRead(self->diagonal_, &d));
  for (PetscInt i : self->fixed_) out[i] = d[i] * in[i];
  PetscCall(VecRestoreArrayRead(self->diagonal_, &d));
  PetscCall(VecRestoreArrayRead(x, &in));
  PetscCall(VecRestoreArray(y, &out));
  PetscFunctionReturn(0);
}

PetscErrorCode MaskedSystem::get_diagonal(Mat W, Vec d) {
  PetscFunctionBeginUser;
  MaskedSystem* self = nullptr;
  PetscCall(MatShellGetContext(W, &self));
  PetscCall(VecCopy(self->diagonal_, d));
  PetscFunctionReturn(0);
}

PetscErrorCode MaskedSystem::wrap(PC outer, PC inner) {
  PetscFunctionBeginUser;
  inner_ = inner;
  PetscCall(PCSetType(outer, PCSHELL));
  PetscCall(PCShellSetContext(outer, this));
  PetscCall(PCShellSetApply(outer, apply));
  PetscCall(PCShellSetName(outer, "masked multigrid"));
  PetscFunctionReturn(0);
}

PetscErrorCode MaskedSystem::apply(PC pc, Vec r, Vec z) {
  PetscFunctionBeginUser;
  MaskedSystem* self = nullptr;
  PetscCall(PCShellGetContext(pc, &self));
  PetscCall(VecCopy(r, self->apply_work_));
  PetscScalar* t = nullptr;
  PetscCall(VecGetArray(self->apply_work_, &t));
  for (PetscInt i : self->fixed_) t[i] = 0;
  PetscCall(VecRestoreArray(self->apply_work_, &t));
  PetscCall(PCApply(self->inner_, self->apply_work_, z));
  PetscScalar* out = nullptr;
  const PetscScalar *in = nullptr, *d = nullptr;
  PetscCall(VecGetArray(z, &out));
  PetscCall(VecGetArrayRead(r, &in));
  PetscCall(VecGetArrayRead(self->diagonal_, &d));
  for (PetscInt i : self->fixed_) out[i] = in[i] / d[i];
  PetscCall(VecRestoreArrayRead(self->diagonal_, &d));
  PetscCall(VecRestoreArrayRead(r, &in));
  PetscCall(VecRestoreArray(z, &out));
  PetscFunctionReturn(0);
}

PetscErrorCode MaskedSystem::system(Vec b, const std::vector<double>& values, Vec x, Vec rhs) {
  PetscFunctionBeginUser;
  // x_X alone, then rhs = b − A x_X on the free rows and diag(A) x_X on the fixed ones.
  PetscCall(VecSet(multiply_work_, 0.0));
  PetscScalar *t = nullptr, *xs = nullptr;
  PetscCall(VecGetArray(multiply_work_, &t));
  PetscCall(VecGetArray(x, &xs));
  for (std::size_t k = 0; k < fixed_.size(); ++k) t[fixed_[k]] = xs[fixed_[k]] = values[k];
  PetscCall(VecRestoreArray(x, &xs));
  PetscCall(VecRestoreArray(multiply_work_, &t));
  PetscCall(MatMult(A_, multiply_work_, rhs));
  PetscCall(VecAYPX(rhs, -1.0, b));
  PetscScalar* out = nullptr;
  const PetscScalar* d = nullptr;
  PetscCall(VecGetArray(rhs, &out));
  PetscCall(VecGetArrayRead(diagonal_, &d));
  for (std::size_t k = 0; k < fixed_.size(); ++k) out[fixed_[k]] = d[fixed_[k]] * values[k];
  PetscCall(VecRestoreArrayRead(diagonal_, &d));
  PetscCall(VecRestoreArray(rhs, &out));
  PetscFunctionReturn(0);
}

}  // namespace contactqp::detail
