// Ipopt, loaded when a run first uses the ipopt backend. Ipopt links Debian's sequential MUMPS,
// which defines stub MPI functions and MUMPS's own names beside PETSc's MPI build of both:
// linked into the program, Ipopt put them in its global symbol scope, where the PETSc plugin's
// calls would find the stubs first, and bound its own MUMPS calls to PETSc's MPI build once PETSc
// was there, which aborts unless MPI runs. As a plugin opened RTLD_LOCAL (qp/plugins.hpp) each
// finds its own MUMPS, and a run that never uses Ipopt never loads it.
// docs/architecture.md, "Plugins".
#pragma once

#include "contactqp/qp.hpp"

namespace contactqp::detail {

// The table the plugin's one exported symbol returns (ipopt_solve.hpp's functions). `abi` must
// equal kIpoptPluginAbi: a plugin from another build of contactqp is refused.
inline constexpr int kIpoptPluginAbi = 1;
struct IpoptPlugin {
  int abi = 0;
  void (*check_options)(const SolveOptions& options) = nullptr;
  SolveResult (*solve)(const QuadraticProgram& qp, const SolveOptions& options) = nullptr;
};

inline constexpr const char* kIpoptPluginFile = "libcontactqp_ipopt.so";
inline constexpr const char* kIpoptPluginSymbol = "contactqp_ipopt_plugin";

}  // namespace contactqp::detail
