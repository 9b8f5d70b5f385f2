// SharedNodes (shared_nodes.hpp): reductions over the holders of each node by PetscSF.
#include "shared_nodes.hpp"

#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "petsc/petsc_runtime.hpp"

namespace contactqp::detail {
namespace {

// `width` entries of `base` as one unit of the SF (a node's entries travel together).
struct Unit {
  MPI_Datatype type = MPI_DATATYPE_NULL;
  Unit(int width, MPI_Datatype base) {
    if (width == 1) {
      type = base;
      return;
    }
    MPI_Type_contiguous(width, base, &type);
    MPI_Type_commit(&type);
  }
  ~Unit() {
    if (type != MPI_DOUBLE && type != MPI_INT) MPI_Type_free(&type);
  }
};

std::size_t size_of(MPI_Datatype type) { return type == MPI_DOUBLE ? sizeof(double) : sizeof(int); }

}  // namespace

SharedNodes::SharedNodes(PetscSF sf, int n_local, int n_owned) : sf_(sf), n_local_(n_local), n_owned_(n_owned) {}

SharedNodes::SharedNodes(SharedNodes&& other) noexcept { *this = std::move(other); }

SharedNodes& SharedNodes::operator=(SharedNodes&& other) noexcept {
  std::swap(sf_, other.sf_);
  std::swap(n_local_, other.n_local_);
  std::swap(n_owned_, other.n_owned_);
  return *this;
}

SharedNodes::~SharedNodes() {
  if (sf_ && !petsc_finalized()) PetscSFDestroy(&sf_);
}

void SharedNodes::combine(void* values, int width, MPI_Datatype type, MPI_Op op) const {
  const Unit unit(width, type);
  const std::size_t bytes = size_of(type) * width;
  // The roots start from the owner's own entries (a leaf too): MPI_SUM adds the others' once.
  // For a maximum or an or they may start from anything the owner has; its own leaf is in it.
  std::vector<char> roots(bytes * n_owned_, 0);
  if (op != MPI_SUM) std::memcpy(roots.data(), values, roots.size());
  check_petsc(PetscSFReduceBegin(sf_, unit.type, values, roots.data(), op), "PetscSFReduceBegin");
  check_petsc(PetscSFReduceEnd(sf_, unit.type, values, roots.data(), op), "PetscSFReduceEnd");
  check_petsc(PetscSFBcastBegin(sf_, unit.type, roots.data(), values, MPI_REPLACE), "PetscSFBcastBegin");
  check_petsc(PetscSFBcastEnd(sf_, unit.type, roots.data(), values, MPI_REPLACE), "PetscSFBcastEnd");
}

void SharedNodes::sum(double* values, int width) const { combine(values, width, MPI_DOUBLE, MPI_SUM); }
void SharedNodes::max(double* values, int width) const { combine(values, width, MPI_DOUBLE, MPI_MAX); }
void SharedNodes::max(int* values, int width) const { combine(values, width, MPI_INT, MPI_MAX); }
void SharedNodes::bitwise_or(int* values, int width) const { combine(values, width, MPI_INT, MPI_BOR); }

void SharedNodes::from_owner(double* values, int width) const {
  const Unit unit(width, MPI_DOUBLE);
  // Owned nodes are local nodes 0 … n_owned − 1, so the owner's entries are the roots' data.
  std::vector<double> roots(values, values + static_cast<std::size_t>(width) * n_owned_);
  check_petsc(PetscSFBcastBegin(sf_, unit.type, roots.data(), values, MPI_REPLACE), "PetscSFBcastBegin");
  check_petsc(PetscSFBcastEnd(sf_, unit.type, roots.data(), values, MPI_REPLACE), "PetscSFBcastEnd");
}

void SharedNodes::from_owner(int* values, int width) const {
  const Unit unit(width, MPI_INT);
  std::vector<int> roots(values, values + static_cast<std::size_t>(width) * n_owned_);
  check_petsc(PetscSFBcastBegin(sf_, unit.type, roots.data(), values, MPI_REPLACE), "PetscSFBcastBegin");
  check_petsc(PetscSFBcastEnd(sf_, unit.type, roots.data(), values, MPI_REPLACE), "PetscSFBcastEnd");
}

}  // namespace contactqp::detail
