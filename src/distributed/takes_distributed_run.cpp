// Which scenes the distributed run takes (run_distributed.hpp). Apart from the run itself, which
// needs PETSc and MPI, because the program decides it before either is loaded (the PETSc
// plugin, src/petsc/petsc_plugin.hpp): a run that does not take this path never loads them.
#include <algorithm>

#include "backend_options.hpp"
#include "contactqp/processes.hpp"
#include "run_distributed.hpp"

namespace contactqp::detail {

// Whether run_scene() goes this way: the petsc backend (with contact, or --no-contact: one
// linear solve by the same KSP and hierarchy, the contact solve's reference) on a one-body
// scene that this path models, under mpirun or with options.distributed (the CLI's default): a
// frictionless scene, with or without load steps, held by prescribed displacements. The others
// keep the one-process path (docs/architecture.md, "Which path a scene takes"), which under
// mpirun holds the mesh and model on every rank and K in rank shares (the problem in parts, as
// for several bodies) rather than refusing them.
bool takes_distributed_run(const Scene& scene, const RunOptions& options) {
  if (scene.solver.backend != Backend::Petsc || !scene.bodies.empty() || !scene.pairs.empty()) return false;
  if (options.whole || (process_count() <= 1 && !options.distributed)) return false;
  if (scene.friction_law() != FrictionLaw::None) return false;
  // A body loaded by forces alone may be one that only its contacts hold, which the one-process
  // path solves on its free motions (docs/extremes.md) and the distributed model refuses.
  const auto displaced = [](const LoadSpec& load) { return load.is<DisplacementLoad>(); };
  if (std::none_of(scene.loads.begin(), scene.loads.end(), displaced)) return false;
  const auto rigid = [](const LoadSpec& load) { return load.is<RigidForceLoad>(); };
  if (std::any_of(scene.loads.begin(), scene.loads.end(), rigid)) return false;
  // The one-process path's own methods (method=tao, hierarchy=fresh), which pdas_options() refuses.
  for (const auto& [key, value] : options_for(Backend::Petsc, scene.solver.backend_options))
    if ((key == "method" && value != "pdas") || (key == "hierarchy" && value != "kept")) return false;
  return true;
}

}  // namespace contactqp::detail
