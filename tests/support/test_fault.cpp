// The faults of the test build's program, contactqp_fault_cli (phases.hpp, PhaseFaults): a
// failure on one process, as one phase begins, as tests/tools/check_rank_faults.py asks for:
//
//   CONTACTQP_TEST_FAULT=RANK:PHASE:KIND[:GRACE]
//
// process RANK throws as PHASE begins — KIND input (InputError, exit 2), error
// (std::runtime_error, exit 1) or memory (std::bad_alloc, exit 1); GRACE (seconds) shortens how
// long the failed process waits for the others. Nothing when the variable is unset; InputError
// naming it when it is malformed. Read on every call (a few times per run). Linked into that
// program only, never into the library or the installed contactqp.
#include <cstdlib>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "contactqp/errors.hpp"
#include "contactqp/phases.hpp"
#include "contactqp/processes.hpp"

namespace contactqp::detail {
namespace {

struct TestFault {
  std::string spec;  // as given
  long rank = -1;
  std::string phase, kind;
  double grace = failure_grace_seconds;
};

// The fault CONTACTQP_TEST_FAULT asks for; rank −1 when it is unset.
TestFault test_fault() {
  TestFault fault;
  const char* text = std::getenv("CONTACTQP_TEST_FAULT");
  if (!text || !*text) return fault;
  fault.spec = text;
  std::vector<std::string> parts;
  std::istringstream fields(fault.spec);
  for (std::string part; std::getline(fields, part, ':');) parts.push_back(part);
  const auto bad = [&fault](const std::string& why) {
    return InputError("CONTACTQP_TEST_FAULT", "= \"" + fault.spec + "\": " + why);
  };
  if (parts.size() < 3 || parts.size() > 4) throw bad("must be RANK:PHASE:KIND or RANK:PHASE:KIND:GRACE");
  char* end = nullptr;
  fault.rank = std::strtol(parts[0].c_str(), &end, 10);
  if (parts[0].empty() || *end || fault.rank < 0) throw bad("RANK must be a process number");
  fault.phase = parts[1];
  fault.kind = parts[2];
  if (fault.kind != "input" && fault.kind != "error" && fault.kind != "memory")
    throw bad("KIND must be input, error or memory");
  if (parts.size() == 4) {
    fault.grace = std::strtod(parts[3].c_str(), &end);
    if (parts[3].empty() || *end || !(fault.grace > 0)) throw bad("GRACE must be a positive number of seconds");
  }
  return fault;
}

double grace_seconds() {
  try {
    return test_fault().grace;
  } catch (const InputError&) {
    return failure_grace_seconds;  // the run has failed on it already
  }
}

void raise_test_fault(const std::string& phase) {
  const TestFault fault = test_fault();
  if (fault.rank != process_rank() || fault.phase != phase) return;
  const std::string where = "injected on rank " + std::to_string(fault.rank) + " as phase " + phase + " begins";
  if (fault.kind == "input") throw InputError("CONTACTQP_TEST_FAULT", "= \"" + fault.spec + "\": a bad input " + where);
  if (fault.kind == "memory") throw std::bad_alloc();
  throw std::runtime_error("CONTACTQP_TEST_FAULT = \"" + fault.spec + "\": an error " + where);
}

// Installed before main() runs: this file is one of the program's own sources.
[[maybe_unused]] const bool installed = (install_phase_faults({&raise_test_fault, &grace_seconds}), true);

}  // namespace
}  // namespace contactqp::detail
