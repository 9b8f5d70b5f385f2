// begin_phase() and checkpoint() (phases.hpp): agree_on_failure() with nothing to report, at
// every boundary, so that a process that failed is met wherever the others are.
#include "run/phases.hpp"

#include "contactqp/processes.hpp"

namespace contactqp::detail {

void checkpoint() {
  if (process_count() <= 1) return;
  // A well process has no line, so it waits as long as the others need: a failed one bounds it.
  const int status = agree_on_failure().status;
  if (status != 0) throw FailedElsewhere(status);
}

void begin_phase(const std::string& phase) {
  checkpoint();
  raise_test_fault(phase);
}

}  // namespace contactqp::detail
