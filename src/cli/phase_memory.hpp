// --phase-memory: the peak resident memory of the process during each phase (Linux: VmHWM of
// /proc/self/status, reset at each phase's start by writing 5 to /proc/self/clear_refs, so a
// phase's peak includes what earlier phases still hold), and the resident memory at each
// phase's start (VmRSS): a phase's own share at its peak is the difference.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace contactqp::cli {

class PhaseMemory {
 public:
  // Ends the phase running (recording its peak) and starts `phase`.
  void start(const std::string& phase);
  // Ends the last phase; two lines, "contactqp: peak memory [MiB]: mesh 12.3, assemble ..." and
  // "contactqp: memory at phase start [MiB]: mesh 8.1, ..." (empty when the kernel gives no
  // VmHWM), `who` after "[MiB]" (" (rank 1)").
  std::string finish(const std::string& who = "");

 private:
  struct Phase {
    std::string name;
    double start_mib = 0, peak_mib = 0;
  };
  std::string phase_;
  double start_mib_ = 0;
  std::vector<Phase> phases_;
};

}  // namespace contactqp::cli
