// MaskedSystem (masked_system.hpp): the step's operator, right-hand side and preconditioner.
#include "masked_system.hpp"

#include "petsc_runtime.hpp"

namespace contactqp::detail {
namespace {

// A pin's projection (masked_system.hpp) on a vector's pair, with d the diagonal of A:
// Π v = v − D⁻¹m (mᵀv)/g, or transposed Πᵀ v = v − m (mᵀD⁻¹v)/g.
void project(const MaskedSystem::Pin& p, const PetscScalar* d, PetscScalar* v, bool transposed) {
  const double g = p.m0 * p.m0 / d[p.i] + p.m1 * p.m1 / d[p.j];
  if (!transposed) {
    const double s = (p.m0 * v[p.i] + p.m1 * v[p.j]) / g;
    v[p.i] -= p.m0 / d[p.i] * s;
    v[p.j] -= p.m1 / d[p.j] * s;
    return;
  }
  const double s = (p.m0 * v[p.i] / d[p.i] + p.m1 * v[p.j] / d[p.j]) / g;
  v[p.i] -= p.m0 * s;
  v[p.j] -= p.m1 * s;
}

// m mᵀv/g (Πᵀ's complement, transposed false) or D⁻¹m mᵀD⁻¹v/g (Π's, true) added to out's pair.
void add_fixed_part(const MaskedSystem::Pin& p, const PetscScalar* d, const PetscScalar* v, PetscScalar* out,
                    bool inverse) {
  const double g = p.m0 * p.m0 / d[p.i] + p.m1 * p.m1 / d[p.j];
  if (!inverse) {
    const double s = (p.m0 * v[p.i] + p.m1 * v[p.j]) / g;
    out[p.i] += p.m0 * s;
    out[p.j] += p.m1 * s;
    return;
  }
  const double s = (p.m0 * v[p.i] / d[p.i] + p.m1 * v[p.j] / d[p.j]) / g;
  out[p.i] += p.m0 / d[p.i] * s;
  out[p.j] += p.m1 / d[p.j] * s;
}

}  // namespace

MaskedSystem::~MaskedSystem() {
  if (petsc_finalized()) return;
  if (W_) MatDestroy(&W_);
  if (W_plain_) MatDestroy(&W_plain_);
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
  PetscCall(MatCreateShell(PetscObjectComm(reinterpret_cast<PetscObject>(A)), local_rows, local_columns, rows, columns,
                           this, &W_plain_));
  PetscCall(MatShellSetOperation(W_plain_, MATOP_MULT, reinterpret_cast<void (*)(void)>(multiply_plain)));
  PetscCall(MatShellSetOperation(W_plain_, MATOP_GET_DIAGONAL, reinterpret_cast<void (*)(void)>(get_diagonal)));
  PetscCall(MatSetOption(W_plain_, MAT_SPD, PETSC_TRUE));
  PetscFunctionReturn(0);
}

PetscErrorCode MaskedSystem::multiply(Mat W, Vec x, Vec y) {
  PetscFunctionBeginUser;
  MaskedSystem* self = nullptr;
  PetscCall(MatShellGetContext(W, &self));
  PetscCall(self->product(x, y, true));
  PetscFunctionReturn(0);
}

PetscErrorCode MaskedSystem::multiply_plain(Mat W, Vec x, Vec y) {
  PetscFunctionBeginUser;
  MaskedSystem* self = nullptr;
  PetscCall(MatShellGetContext(W, &self));
  PetscCall(self->product(x, y, false));
  PetscFunctionReturn(0);
}

PetscErrorCode MaskedSystem::product(Vec x, Vec y, bool with_blocks) {
  PetscFunctionBeginUser;
  PetscCall(VecCopy(x, multiply_work_));
  PetscScalar* t = nullptr;
  const PetscScalar* d = nullptr;
  PetscCall(VecGetArrayRead(diagonal_, &d));
  PetscCall(VecGetArray(multiply_work_, &t));
  for (PetscInt i : fixed_) t[i] = 0;
  for (const Pin& p : pins_) project(p, d, t, false);
  PetscCall(VecRestoreArray(multiply_work_, &t));
  PetscCall(MatMult(A_, multiply_work_, y));
  PetscScalar* out = nullptr;
  const PetscScalar* in = nullptr;
  PetscCall(VecGetArray(y, &out));
  PetscCall(VecGetArrayRead(x, &in));
  for (PetscInt i : fixed_) out[i] = d[i] * in[i];
  for (const Pin& p : pins_) {
    project(p, d, out, true);
    add_fixed_part(p, d, in, out, false);
  }
  for (const Block& block : blocks_) {
    if (!with_blocks) break;
    if (block.j < 0) {
      out[block.i] += block.a11 * in[block.i];
      continue;
    }
    out[block.i] += block.a11 * in[block.i] + block.a12 * in[block.j];
    out[block.j] += block.a12 * in[block.i] + block.a22 * in[block.j];
  }
  PetscCall(VecRestoreArrayRead(diagonal_, &d));
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
  const PetscScalar* d = nullptr;
  PetscCall(VecGetArrayRead(self->diagonal_, &d));
  PetscCall(VecGetArray(self->apply_work_, &t));
  for (PetscInt i : self->fixed_) t[i] = 0;
  for (const Pin& p : self->pins_) project(p, d, t, true);
  PetscCall(VecRestoreArray(self->apply_work_, &t));
  PetscCall(PCApply(self->inner_, self->apply_work_, z));
  PetscScalar* out = nullptr;
  const PetscScalar* in = nullptr;
  PetscCall(VecGetArray(z, &out));
  PetscCall(VecGetArrayRead(r, &in));
  for (PetscInt i : self->fixed_) out[i] = in[i] / d[i];
  for (const Pin& p : self->pins_) {
    project(p, d, out, false);
    add_fixed_part(p, d, in, out, true);
  }
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
  const PetscScalar* d = nullptr;
  PetscCall(VecGetArrayRead(diagonal_, &d));
  for (std::size_t k = 0; k < fixed_.size(); ++k) t[fixed_[k]] = xs[fixed_[k]] = values[k];
  for (const Pin& p : pins_) {
    // x_X on a pin: D⁻¹m value/g, the part along D⁻¹m with mᵀx_X = value; x's is replaced by it.
    const double g = p.m0 * p.m0 / d[p.i] + p.m1 * p.m1 / d[p.j];
    project(p, d, xs, false);
    t[p.i] = p.m0 / d[p.i] * p.value / g;
    t[p.j] = p.m1 / d[p.j] * p.value / g;
    xs[p.i] += t[p.i];
    xs[p.j] += t[p.j];
  }
  PetscCall(VecRestoreArray(x, &xs));
  PetscCall(VecRestoreArray(multiply_work_, &t));
  PetscCall(MatMult(A_, multiply_work_, rhs));
  PetscCall(VecAYPX(rhs, -1.0, b));
  PetscScalar* out = nullptr;
  PetscCall(VecGetArray(rhs, &out));
  for (std::size_t k = 0; k < fixed_.size(); ++k) out[fixed_[k]] = d[fixed_[k]] * values[k];
  for (const Pin& p : pins_) {
    // Πᵀ (b − A x_X) + m value/g.
    const double g = p.m0 * p.m0 / d[p.i] + p.m1 * p.m1 / d[p.j];
    project(p, d, out, true);
    out[p.i] += p.m0 * p.value / g;
    out[p.j] += p.m1 * p.value / g;
  }
  PetscCall(VecRestoreArrayRead(diagonal_, &d));
  PetscCall(VecRestoreArray(rhs, &out));
  PetscFunctionReturn(0);
}

}  // namespace contactqp::detail
