// The program's side of the PETSc plugin (petsc_plugin.hpp): the functions that the room's
// plugin-free files (cqp_petsc_common) and its registrations (petsc_registrations.cpp) call,
// each calling the plugin's own. The plugin is opened by the first call that needs PETSc or MPI
// running; until then a process is one of those its launcher started (processes.hpp reads the
// launcher's environment), and nothing of PETSc or MPI is loaded.
#include <atomic>
#include <mutex>

#include "contactqp/petsc/par_qp.hpp"
#include "distributed/run_distributed.hpp"
#include "mpi.hpp"
#include "petsc_plugin.hpp"
#include "qp/plugins.hpp"

namespace contactqp::detail {
namespace {

std::atomic<const PetscPlugin*> opened{nullptr};

// The plugin, opened on the first call (thread-safe); throws std::runtime_error "PETSc is
// unavailable: ..." when it cannot be opened, and the next call tries again. The faults the
// program installed for its tests are installed in the plugin's copy of the phases too.
const PetscPlugin& plugin() {
  if (const PetscPlugin* table = opened.load()) return *table;
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  if (!opened.load()) {
    const PetscPlugin& table =
        open_plugin_table<PetscPlugin>(kPetscPluginFile, kPetscPluginSymbol, kPetscPluginAbi, "PETSc");
    table.install_phase_faults(installed_phase_faults());
    opened = &table;
  }
  return *opened.load();
}

}  // namespace

// Not running before the plugin is open: MPI starts only through it.
int mpi_rank() { return opened.load() ? plugin().mpi_rank() : -1; }
int mpi_size() { return opened.load() ? plugin().mpi_size() : 0; }
void sum_over_ranks(double* values, long n) {
  if (opened.load()) plugin().sum_over_ranks(values, n);  // else one rank: nothing to sum
}
void connect_mpi() { plugin().connect_mpi(); }
AgreedFailure mpi_agree_on_failure(int status, const std::string& error, double timeout_seconds) {
  if (!opened.load()) return {status, error, error.empty() ? -1 : 0, !error.empty()};  // one process
  return plugin().mpi_agree_on_failure(status, error, timeout_seconds);
}
void start_petsc_runtime(const std::map<std::string, std::string>& library_options) {
  plugin().start_petsc_runtime(library_options);
}

std::shared_ptr<const LinearSolver> make_petsc_solver(const Eigen::SparseMatrix<double>& A,
                                                      const LinearSolverOptions& options, const MatrixLayout& layout) {
  return plugin().make_petsc_solver(A, options, layout);
}

BoundQpResult solve_bound_qp_petsc(BoundQp problem, const BoundQpOptions& options, BoundQpChain* chain) {
  return plugin().solve_bound_qp_petsc(std::move(problem), options, chain);
}

RunReport run_distributed(const Scene& scene, const RunOptions& options) {
  return plugin().run_distributed(scene, options);
}

}  // namespace contactqp::detail

namespace contactqp {

std::vector<int> partition_graph(const std::vector<long>& offsets, const std::vector<int>& neighbours, int parts,
                                 const std::string& petsc_options) {
  return detail::plugin().partition_graph(offsets, neighbours, parts, petsc_options);
}

}  // namespace contactqp
