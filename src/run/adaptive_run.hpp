// The adaptive run of a scene with "adapt" (docs/adaptive.md); run_scene() calls it.
#pragma once

#include "contactqp/io.hpp"
#include "contactqp/run.hpp"

namespace contactqp::detail {

// Runs the scene (its "adapt" set) cycle after cycle, each on one process with the estimate:
// the first on the scene's own mesh, each next one on a mesh whose generated bodies Gmsh meshes
// with the sizes plan_next_mesh() gives (mesh-file bodies keep theirs), until η / sqrt(2E) is at
// most adapt.target, a cycle does not converge, the next mesh would exceed adapt.max_dofs, or
// adapt.max_cycles are spent. Returns the last cycle's report with RunReport::adaptive set.
// InputError under mpirun, with the estimate off, or with no generated body.
RunReport run_adaptive(const Scene& scene, const RunOptions& options);

}  // namespace contactqp::detail
