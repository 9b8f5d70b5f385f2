// PETSc and MPI, loaded when a run first needs them. PETSc and what it links (Trilinos, HDF5,
// hypre, MUMPS, curl, X11, ...: about 60 shared libraries) took 0.06-0.1 s of every start of
// the program, also of the runs that never use it: --version, a scene refused for a bad key,
// every backend but petsc. So the room's code that calls PETSc or MPI (the files of cqp_petsc
// that are not also in cqp_petsc_common, and the distributed run) is a plugin,
// libcontactqp_petsc.so, opened with dlopen on first use (qp/plugins.hpp); the program links
// petsc_plugin_calls.cpp in their place, which defines the same functions by calling the
// plugin's. docs/architecture.md, "Plugins".
//
// The plugin holds its own copy of the library's code, so what the program installs in its
// copy at run time reaches the plugin's through this table too (the test build's phase faults).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "contactqp/phases.hpp"
#include "contactqp/processes.hpp"
#include "contactqp/run.hpp"
#include "petsc_bound_qp.hpp"
#include "petsc_solver.hpp"

namespace contactqp::detail {

// The table the plugin's one exported symbol returns. `abi` must equal kPetscPluginAbi: a plugin
// from another build of contactqp is refused rather than called with other struct layouts.
inline constexpr int kPetscPluginAbi = 2;
struct PetscPlugin {
  int abi = 0;
  // mpi.hpp
  int (*mpi_rank)() = nullptr;
  int (*mpi_size)() = nullptr;
  void (*sum_over_ranks)(double* values, long n) = nullptr;
  void (*connect_mpi)() = nullptr;
  AgreedFailure (*mpi_agree_on_failure)(int status, const std::string& error, double timeout_seconds) = nullptr;
  void (*start_petsc_runtime)(const std::map<std::string, std::string>& library_options) = nullptr;
  // petsc_solver.hpp, petsc_bound_qp.hpp, contactqp/petsc/par_qp.hpp
  std::shared_ptr<const LinearSolver> (*make_petsc_solver)(const Eigen::SparseMatrix<double>& A,
                                                           const LinearSolverOptions& options,
                                                           const MatrixLayout& layout) = nullptr;
  BoundQpResult (*solve_bound_qp_petsc)(BoundQp problem, const BoundQpOptions& options, BoundQpChain* chain) = nullptr;
  std::vector<int> (*partition_graph)(const std::vector<long>& offsets, const std::vector<int>& neighbours, int parts,
                                      const std::string& petsc_options) = nullptr;
  // distributed/run_distributed.hpp
  RunReport (*run_distributed)(const Scene& scene, const RunOptions& options) = nullptr;
  // contactqp/phases.hpp: the program's faults, installed in the plugin's copy as it opens.
  void (*install_phase_faults)(const PhaseFaults& faults) = nullptr;
};

// The file name, and the symbol the plugin exports (extern "C", returning its table).
inline constexpr const char* kPetscPluginFile = "libcontactqp_petsc.so";
inline constexpr const char* kPetscPluginSymbol = "contactqp_petsc_plugin";

}  // namespace contactqp::detail
