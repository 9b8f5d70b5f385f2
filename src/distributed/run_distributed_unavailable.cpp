// run_distributed.hpp without PETSc: no run is distributed.
#include <stdexcept>

#include "distributed/run_distributed.hpp"

namespace contactqp::detail {

bool runs_distributed(const Scene&, const RunOptions&) { return false; }

RunReport run_scene_distributed(const Scene&, const RunOptions&) {
  throw std::logic_error("run_scene_distributed: contactqp was built without PETSc");
}

}  // namespace contactqp::detail
