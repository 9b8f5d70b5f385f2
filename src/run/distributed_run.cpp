// The registered distributed runs (distributed_run.hpp).
#include "run/distributed_run.hpp"

#include <stdexcept>
#include <vector>

#include "contactqp/errors.hpp"
#include "qp/builtins.hpp"
#include "qp/registrations.hpp"

namespace contactqp::detail {
namespace {

Registrations<DistributedRun>& distributed_runs() {
  static Registrations<DistributedRun> all;
  return all;
}

// The first registered run that takes the scene, or null.
const DistributedRun* taker(const Scene& scene, const RunOptions& options, std::vector<DistributedRun>& runs) {
  register_builtins();
  runs = distributed_runs().copy();
  for (const DistributedRun& run : runs)
    if (run.takes(scene, options)) return &run;
  return nullptr;
}

}  // namespace

void register_distributed_run(DistributedRun run) { distributed_runs().add(std::move(run)); }

void refuse_held_by_contact_on_several_processes(Backend backend, const std::string& motion) {
  throw InputError("backend", "= \"" + to_string(backend) + "\": a body held only by its contacts (it moves freely " +
                                  motion +
                                  " without them) is not solved on several processes by this backend yet: run on "
                                  "one process, or with another backend");
}

RunReport run_scene_distributed(const Scene& scene, const RunOptions& options) {
  std::vector<DistributedRun> runs;
  const DistributedRun* run = taker(scene, options, runs);
  if (!run) throw std::logic_error("run_scene_distributed: no distributed run takes this scene");
  return run->run(scene, options);
}

}  // namespace contactqp::detail

namespace contactqp {

bool runs_distributed(const Scene& scene, const RunOptions& options) {
  std::vector<detail::DistributedRun> runs;
  return detail::taker(scene, options, runs) != nullptr;
}

}  // namespace contactqp
