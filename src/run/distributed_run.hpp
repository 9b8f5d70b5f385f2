// A run in which no process holds the whole mesh, model or output (docs/petsc-design.md, "Distributed
// runs"): each process meshes, assembles, solves and writes only its part. run_scene() hands the
// whole run to it when one is registered and takes the scene and options; the library that
// knows about processes registers it from its own file (src/distributed/ does, for the petsc
// backend under mpirun), so that nothing here knows about ranks.
#pragma once

#include <functional>

#include "contactqp/run.hpp"

namespace contactqp::detail {

struct DistributedRun {
  std::function<bool(const Scene& scene, const RunOptions& options)> takes;
  // What run_scene() does, distributed; the .pvtu's pieces through RunReport::write_pieces. Collective.
  std::function<RunReport(const Scene& scene, const RunOptions& options)> run;
};
void register_distributed_run(DistributedRun run);

// The run of the first registered distributed run that takes it. Collective.
RunReport run_scene_distributed(const Scene& scene, const RunOptions& options);

// A body only its contacts hold (it moves freely `motion`, e.g. "along +y", without them), which
// neither the distributed run nor a problem held in parts solves yet: one refusal for both
// (InputError naming "backend").
[[noreturn]] void refuse_held_by_contact_on_several_processes(Backend backend, const std::string& motion);

}  // namespace contactqp::detail
