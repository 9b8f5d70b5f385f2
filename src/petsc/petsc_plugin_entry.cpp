// The PETSc plugin's one exported symbol: its table of functions (petsc_plugin.hpp). Everything
// else the plugin holds is hidden (linked with --exclude-libs,ALL).
#include "contactqp/petsc/par_qp.hpp"
#include "distributed/run_distributed.hpp"
#include "mpi.hpp"
#include "petsc_plugin.hpp"

namespace {

contactqp::detail::PetscPlugin make_table() {
  using namespace contactqp::detail;
  PetscPlugin table;
  table.abi = kPetscPluginAbi;
  table.mpi_rank = &mpi_rank;
  table.mpi_size = &mpi_size;
  table.sum_over_ranks = &sum_over_ranks;
  table.connect_mpi = &connect_mpi;
  table.mpi_agree_on_failure = &mpi_agree_on_failure;
  table.start_petsc_runtime = &start_petsc_runtime;
  table.make_petsc_solver = &make_petsc_solver;
  table.solve_bound_qp_petsc = &solve_bound_qp_petsc;
  table.partition_graph = &contactqp::partition_graph;
  table.run_distributed = &run_distributed;
  table.install_phase_faults = &contactqp::install_phase_faults;
  return table;
}

}  // namespace

// Returns const void*, the type open_plugin() (plugins.cpp) calls it through: a call through a
// pointer to another function type is undefined (Clang's -fsanitize=function stops on it).
extern "C" __attribute__((visibility("default"))) const void* contactqp_petsc_plugin() {
  static const contactqp::detail::PetscPlugin table = make_table();
  return &table;
}
