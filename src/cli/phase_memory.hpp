// --phase-memory: the peak resident memory of the process during each phase (Linux: VmHWM of
// /proc/self/status, reset at each phase's start by writing 5 to /proc/self/clear_refs, so a
// phase's peak includes what earlier phases still hold).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace contactqp::cli {

class PhaseMemory {
 public:
  // Ends the phase running (recording its peak) and starts `phase`.
  void start(const std::string& phase);
  // Ends the last phase; one line "contactqp: peak memory [MiB]: mesh 12.3, assemble ..." (empty
  // when the kernel gives no VmHWM).
  std::string finish();

 private:
  std::string phase_;
  std::vector<std::pair<std::string, double>> peaks_;
};

}  // namespace contactqp::cli
