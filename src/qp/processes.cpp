// process_rank(), process_count(), start_process_runtime() and agree_on_failure() (processes.hpp):
// the launcher's environment, or the runtime a library registered once it runs.
#include "contactqp/processes.hpp"

#include <cstdlib>
#include <iostream>
#include <mutex>
#include <string>

#include "qp/builtins.hpp"

namespace contactqp {
namespace {

struct Registered {
  std::mutex mutex;
  ProcessRuntime runtime;
};

Registered& registered() {
  static Registered one;
  return one;
}

ProcessRuntime runtime() {
  detail::register_builtins();
  Registered& r = registered();
  std::lock_guard<std::mutex> lock(r.mutex);
  return r.runtime;
}

// The launcher's value of one of `names` (OpenMPI, PMIx, MPICH's PMI), or -1.
int launcher_value(std::initializer_list<const char*> names) {
  for (const char* name : names)
    if (const char* text = std::getenv(name)) {
      char* end = nullptr;
      const long value = std::strtol(text, &end, 10);
      if (end != text && *end == '\0' && value >= 0) return static_cast<int>(value);
    }
  return -1;
}

// The number of processes the registered runtime runs on, 0 when it does not run.
int running_count(const ProcessRuntime& r) { return r.count ? r.count() : 0; }

}  // namespace

void register_process_runtime(ProcessRuntime runtime) {
  Registered& r = registered();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.runtime = std::move(runtime);
}

int process_rank() {
  const ProcessRuntime r = runtime();
  const int rank = r.rank ? r.rank() : -1;
  if (rank >= 0) return rank;
  const int launched = launcher_value({"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"});
  return launched >= 0 ? launched : 0;
}

int process_count() {
  const int size = running_count(runtime());
  if (size >= 1) return size;
  const int launched = launcher_value({"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"});
  return launched >= 1 ? launched : 1;
}

void connect_processes() {
  const ProcessRuntime r = runtime();
  if (r.connect) r.connect();
}

void start_process_runtime(const std::map<std::string, std::string>& library_options) {
  const ProcessRuntime r = runtime();
  if (r.start) r.start(library_options);
}

AgreedFailure agree_on_failure(int status, const std::string& error, double timeout_seconds) {
  const ProcessRuntime r = runtime();
  if (running_count(r) > 1) return r.agree_on_failure(status, error, timeout_seconds);
  // No runtime between the processes (one process, or a failure before it started, the same on
  // every process): each decides alone, and process 0 speaks for all.
  AgreedFailure agreed;
  agreed.status = status;
  agreed.error = error;
  agreed.process = error.empty() ? -1 : 0;
  agreed.everywhere = !error.empty();
  return agreed;
}

}  // namespace contactqp
