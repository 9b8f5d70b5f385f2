// The primal interior-point backend: Ipopt (with Debian's sequential MUMPS) on the QP itself
// (ipopt/ipopt_solve.cpp has the formulation). Its registration is here, known before Ipopt is
// loaded; the work is in the Ipopt plugin (ipopt/ipopt_plugin.hpp), opened by the first check
// of its options or the first solve.
#include <dlfcn.h>

#include "backends.hpp"

#ifdef CONTACTQP_HAVE_IPOPT  // set by CMake when Ipopt was found (CONTACTQP_WITH_IPOPT)
#include <mutex>

#include "contactqp/processes.hpp"
#include "ipopt/ipopt_plugin.hpp"
#include "qp/plugins.hpp"

namespace contactqp::detail {
namespace {

// The plugin, opened on the first call (thread-safe); std::runtime_error "Ipopt is unavailable:
// ..." when it cannot be, and the next call tries again.
const IpoptPlugin& ipopt_plugin() {
  static std::mutex mutex;
  static const IpoptPlugin* table = nullptr;
  std::lock_guard<std::mutex> lock(mutex);
  if (!table) table = &open_plugin_table<IpoptPlugin>(kIpoptPluginFile, kIpoptPluginSymbol, kIpoptPluginAbi, "Ipopt");
  return *table;
}

SolveResult solve_by_plugin(const QuadraticProgram& qp, const SolveOptions& options) {
  // A program that links PETSc itself (the test build, the sanitizer build) holds PETSc's MPI
  // build of MUMPS in its global scope, where Ipopt's MUMPS calls find it before the plugin's
  // own sequential one: MPI must be running then. Its start-up, once per process, is timed
  // apart so that Ipopt's own phases stay comparable.
  Stopwatch start_clock;
  if (dlsym(RTLD_DEFAULT, "dmumps_c")) start_process_runtime(options.library_options);
  const double start_seconds = start_clock.seconds();
  SolveResult result = ipopt_plugin().solve(qp, options);
  if (start_seconds > 1e-3) {
    Timings timings;
    timings.add("petsc_start", start_seconds);
    timings.merge(result.timings);
    result.timings = timings;
  }
  return result;
}

}  // namespace
}  // namespace contactqp::detail
#endif  // CONTACTQP_HAVE_IPOPT

CONTACTQP_BUILTIN(ipopt) {
  BackendRegistration ipopt;
  ipopt.name = "ipopt";
  ipopt.summary = "primal interior point (Ipopt with MUMPS) on the QP itself";
  ipopt.order = 30;
  ipopt.option_names = {"print_level", "max_iter", "tol", "mu_strategy", "mu_init"};
  ipopt.library_options = true;  // any of Ipopt's own options, checked against Ipopt's list
#ifdef CONTACTQP_HAVE_IPOPT
  ipopt.check_options = [](const SolveOptions& options) { ipopt_plugin().check_options(options); };
  ipopt.solve = solve_by_plugin;
  ipopt.problem_kinds = {ProblemKind::Frictionless, ProblemKind::Tresca, ProblemKind::Coulomb};
#else
  ipopt.available = false;
#endif
  register_backend(ipopt);
}
