// The registered distributed runs (distributed_run.hpp).
#include "run/distributed_run.hpp"

#include <mutex>
#include <stdexcept>
#include <vector>

#include "qp/builtins.hpp"

namespace contactqp::detail {
namespace {

struct Registered {
  std::mutex mutex;
  std::vector<DistributedRun> runs;
};

Registered& registered() {
  static Registered all;
  return all;
}

// The first registered run that takes the scene, or null.
const DistributedRun* taker(const Scene& scene, const RunOptions& options, std::vector<DistributedRun>& runs) {
  register_builtins();
  {
    Registered& r = registered();
    std::lock_guard<std::mutex> lock(r.mutex);
    runs = r.runs;
  }
  for (const DistributedRun& run : runs)
    if (run.takes(scene, options)) return &run;
  return nullptr;
}

}  // namespace

void register_distributed_run(DistributedRun run) {
  Registered& r = registered();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.runs.push_back(std::move(run));
}

bool runs_distributed(const Scene& scene, const RunOptions& options) {
  std::vector<DistributedRun> runs;
  return taker(scene, options, runs) != nullptr;
}

RunReport run_scene_distributed(const Scene& scene, const RunOptions& options) {
  std::vector<DistributedRun> runs;
  const DistributedRun* run = taker(scene, options, runs);
  if (!run) throw std::logic_error("run_scene_distributed: no distributed run takes this scene");
  return run->run(scene, options);
}

}  // namespace contactqp::detail
