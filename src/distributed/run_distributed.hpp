// run_scene() with each process holding only its part of everything that grows with the mesh
// (docs/petsc.md, "Distributed runs"): the mesh, the model, A = QᵀKQ, the vectors and the
// ParaView output. Taken for the petsc backend under mpirun (or with RunOptions::distributed);
// the report is run_scene()'s, the summary and the result files on rank 0, and every rank writes
// its piece of the .pvtu through RunReport::write_pieces.
#pragma once

#include "contactqp/run.hpp"

namespace contactqp::detail {

// Whether run_scene() goes this way: the petsc backend with contact, a one-body scene, and
// several processes or options.distributed. False when contactqp was built without PETSc.
bool runs_distributed(const Scene& scene, const RunOptions& options);

// Collective. What run_scene() does, distributed.
RunReport run_scene_distributed(const Scene& scene, const RunOptions& options);

}  // namespace contactqp::detail
