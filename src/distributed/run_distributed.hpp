// The distributed run (docs/petsc-design.md, "Distributed runs"): run_scene() with each process
// holding only its part of everything that grows with the mesh. run_distributed.cpp registers
// it with run_scene() (run/distributed_run.hpp) where the PETSc room is linked in; the PETSc
// plugin's callers register the same two functions, the run reached through the plugin.
#pragma once

#include "contactqp/run.hpp"

namespace contactqp::detail {

// Whether run_scene() goes this way (takes_distributed_run.cpp: needs neither PETSc nor MPI).
bool takes_distributed_run(const Scene& scene, const RunOptions& options);

// What run_scene() does, distributed. Collective.
RunReport run_distributed(const Scene& scene, const RunOptions& options);

}  // namespace contactqp::detail
