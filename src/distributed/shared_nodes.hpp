// The nodes of a distributed mesh that several ranks hold (distributed_mesh.hpp), through one
// PetscSF: every node is a root on the rank that owns it and a leaf on every rank that holds it,
// its owner included. A per-node quantity built from a rank's own elements and faces (a sum over
// faces, a flag set by a boundary) becomes the whole mesh's by a reduction to the owner and a
// broadcast back, so that every holder sees the same number.
#pragma once

#include <petscsf.h>

#include <vector>

namespace contactqp::detail {

class SharedNodes {
 public:
  SharedNodes() = default;
  // Takes `sf` (leaves: the n_local nodes of this rank, roots: its n_owned own nodes, which are
  // local nodes 0 … n_owned − 1).
  SharedNodes(PetscSF sf, int n_local, int n_owned);
  SharedNodes(SharedNodes&& other) noexcept;
  SharedNodes& operator=(SharedNodes&& other) noexcept;
  SharedNodes(const SharedNodes&) = delete;
  SharedNodes& operator=(const SharedNodes&) = delete;
  ~SharedNodes();

  int n_local() const { return n_local_; }
  int n_owned() const { return n_owned_; }
  PetscSF sf() const { return sf_; }

  // In place on every rank, `width` entries per local node: each node's entries become their
  // sum (max, bitwise or) over the ranks that hold it. Collective.
  void sum(double* values, int width) const;
  void max(double* values, int width) const;
  void max(int* values, int width) const;
  void bitwise_or(int* values, int width) const;
  // The owner's entries to every holder (the others' are overwritten). Collective.
  void from_owner(double* values, int width) const;
  void from_owner(int* values, int width) const;

 private:
  void combine(void* values, int width, MPI_Datatype type, MPI_Op op) const;

  PetscSF sf_ = nullptr;
  int n_local_ = 0, n_owned_ = 0;
};

}  // namespace contactqp::detail
