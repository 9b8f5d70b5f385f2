// The phases of a run and the boundaries between them, where the processes of a run launched
// together (mpirun) agree that none has failed (docs/petsc.md, "When one rank fails"), by the
// one protocol, agree_on_failure() (processes.hpp). A process that fails leaves its phase at once
// for main(), which hands its status and its error to agree_on_failure(); the others meet that
// call at their next boundary, learn the status there and end with it, quietly: the failed
// process prints its line, once.
//
// The rule for phase code: work that can fail on one process alone (reading, checking, element
// loops, allocations) goes before the phase's first call that needs every process (a collective
// of MPI or PETSc), or a checkpoint() goes between them. A process that fails while the others
// are inside such a call waits a bounded time for them, prints its line and ends them all.
#pragma once

#include <exception>
#include <string>

namespace contactqp {

// Thrown on a process that learns at a boundary that another process failed. main() ends
// with `status` and says nothing: the process that failed printed the line. No agreement
// follows (the failed process made its last one).
class FailedElsewhere : public std::exception {
 public:
  explicit FailedElsewhere(int status) : status_(status) {}
  int status() const { return status_; }
  const char* what() const noexcept override { return "another process of the run failed"; }

 private:
  int status_;
};

// Called by every process as `phase` begins: agrees with the others that none has failed
// (collective on several processes, nothing on one), then raises the fault this phase has if a
// test build installed one (PhaseFaults below). Throws FailedElsewhere.
void begin_phase(const std::string& phase);

// The same agreement within a phase: after local work that can fail on some processes only
// (rank 0 meshing the coarse body, one rank's part holding a bad value) and before the
// collective that follows it, and before output files are renamed into place (nothing is
// written unless every process got there). Throws FailedElsewhere; nothing on one process.
void checkpoint();

// How long a process that failed waits for the others to reach a boundary before it prints its
// line and ends them all (agree_on_failure): failure_grace_seconds (30 s), or the installed
// faults' grace_seconds().
double failed_process_grace_seconds();

// Failures injected as phases begin, for the tests of a failure on one process only. The library
// and the installed program carry none: the test build's program contactqp_fault_cli installs
// them (tests/support/test_fault.cpp: CONTACTQP_TEST_FAULT=RANK:PHASE:KIND[:GRACE]). `raise` is
// called as each phase begins, `grace_seconds` replaces failure_grace_seconds.
struct PhaseFaults {
  void (*raise)(const std::string& phase) = nullptr;
  double (*grace_seconds)() = nullptr;
};
void install_phase_faults(const PhaseFaults& faults);
// The faults installed (none: both pointers null). A library loaded later installs them in its
// own copy of this code (the PETSc plugin does).
PhaseFaults installed_phase_faults();

}  // namespace contactqp
