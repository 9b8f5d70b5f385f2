#include "phase_memory.hpp"

#include <fstream>
#include <sstream>

#include "commands.hpp"

namespace contactqp::cli {
namespace {

// A line of /proc/self/status ("VmHWM:", "VmRSS:") in MiB, or a negative number without it.
double status_mib(const std::string& key) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind(key, 0) == 0) {
      std::istringstream fields(line.substr(key.size()));
      double kib = -1;
      fields >> kib;
      return kib / 1024;
    }
  return -1;
}

void reset_peak() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
}

}  // namespace

void PhaseMemory::start(const std::string& phase) {
  if (!phase_.empty()) phases_.push_back({phase_, start_mib_, status_mib("VmHWM:")});
  phase_ = phase;
  start_mib_ = status_mib("VmRSS:");
  reset_peak();
}

std::string PhaseMemory::finish(const std::string& who) {
  start("");
  std::string peaks = "contactqp: peak memory [MiB]" + who + ":";
  std::string starts = "contactqp: memory at phase start [MiB]" + who + ":";
  for (const Phase& phase : phases_) {
    if (phase.peak_mib < 0) return "";
    peaks += format(" %s %.1f,", phase.name.c_str(), phase.peak_mib);
    starts += format(" %s %.1f,", phase.name.c_str(), phase.start_mib);
  }
  peaks.back() = '\n';
  starts.back() = '\n';
  return peaks + starts;
}

}  // namespace contactqp::cli
