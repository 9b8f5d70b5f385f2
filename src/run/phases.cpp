// begin_phase() and checkpoint() (phases.hpp): agree_on_failure() with nothing to report, at
// every boundary, so that a process that failed is met wherever the others are.
#include "contactqp/phases.hpp"

#include "contactqp/processes.hpp"

namespace contactqp {
namespace {

PhaseFaults& installed_faults() {
  static PhaseFaults faults;
  return faults;
}

}  // namespace

void install_phase_faults(const PhaseFaults& faults) { installed_faults() = faults; }

PhaseFaults installed_phase_faults() { return installed_faults(); }

double failed_process_grace_seconds() {
  const PhaseFaults& faults = installed_faults();
  return faults.grace_seconds ? faults.grace_seconds() : failure_grace_seconds;
}

void checkpoint() {
  if (process_count() <= 1) return;
  // A well process has no line, so it waits as long as the others need: a failed one bounds it.
  const int status = agree_on_failure().status;
  if (status != 0) throw FailedElsewhere(status);
}

void begin_phase(const std::string& phase) {
  checkpoint();
  if (const PhaseFaults& faults = installed_faults(); faults.raise) faults.raise(phase);
}

}  // namespace contactqp
