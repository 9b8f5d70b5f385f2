#include "phase_memory.hpp"

#include <fstream>
#include <sstream>

#include "commands.hpp"

namespace contactqp::cli {
namespace {

// VmHWM in MiB, or a negative number when /proc does not give it.
double peak_resident_mib() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) {
      std::istringstream fields(line.substr(6));
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
  if (!phase_.empty()) peaks_.emplace_back(phase_, peak_resident_mib());
  phase_ = phase;
  reset_peak();
}

std::string PhaseMemory::finish() {
  start("");
  std::string line = "contactqp: peak memory [MiB]:";
  for (const auto& [phase, mib] : peaks_) {
    if (mib < 0) return "";
    line += format(" %s %.1f,", phase.c_str(), mib);
  }
  line.back() = '\n';
  return line;
}

}  // namespace contactqp::cli
