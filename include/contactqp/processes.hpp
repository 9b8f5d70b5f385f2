// Several processes started together by a launcher (mpirun, docs/petsc.md): which one this is,
// and how they end together. A library that runs them together registers its runtime here
// (src/petsc/ does, with MPI through PETSc); without one, or before it starts, each process
// reads only what the launcher put in its environment.
#pragma once

#include <functional>
#include <map>
#include <string>

namespace contactqp {

// This process's index among those launched together, once the runtime runs; before that the
// launcher's (OMPI_COMM_WORLD_RANK, PMIX_RANK or PMI_RANK in the environment), else 0. Only
// process 0 prints and writes files.
int process_rank();
// The number of processes launched together (the launcher's count before the runtime runs), else 1.
int process_count();

// Starts the runtime of several processes now, once per process, if one is built in; a no-op
// otherwise. `library_options` (SolveOptions::library_options) are its libraries' options, the
// command line it starts with. A library whose calls need it running calls it first: in a
// program that links PETSc itself, Ipopt's MUMPS resolves to PETSc's MPI build, which aborts
// without MPI (solvers/ipopt.cpp).
void start_process_runtime(const std::map<std::string, std::string>& library_options = {});

// Connects the processes launched together (MPI alone, no library on it yet), once per process,
// if a runtime is built in; nothing otherwise. main() calls it first when the launcher says there
// are several, so that every failure, even in reading the scene, is agreed at the next phase
// boundary (contactqp/phases.hpp). start_process_runtime() later finds the connection and uses it.
void connect_processes();

// What the processes agreed on (agree_on_failure()).
struct AgreedFailure {
  int status = 0;           // the largest status passed: 0 when no process failed
  std::string error;        // the error of the lowest-numbered process that passed one; "" when none did
  int process = -1;         // that process; −1 when none
  bool everywhere = false;  // every process passed an error (else the error is one process's own)
};

// The one protocol by which the processes of a run agree on a failure (docs/petsc.md, "When one
// rank fails"). Every process calls it at the same point with its status and its error (0 and
// "" when it has not failed) and learns the largest status and the first process's error:
//   - at a boundary, a process that has not failed (phases.hpp's checkpoint(), every phase
//     and step of a run), where one that failed meets it from main() with its exit status and
//     error line (its last agreement: it left the run when it failed);
//   - within a step whose failure every process must know to take the same branch, each with
//     its own outcome (the petsc backend's set-up and iteration).
// Collective while the runtime runs on several processes; on one (or before the runtime runs,
// when every process fails alike) it returns the caller's own, process 0 speaking. A process
// that failed waits at most `timeout_seconds` for the others (they may be stuck in a collective
// call it left), then prints its error ("contactqp: error: ...") and ends them all: never a
// hang. 30 s: long enough for the others to reach a boundary from any phase of a large run's
// step, short enough that a run stuck in a collective ends well within a minute.
constexpr double failure_grace_seconds = 30;
AgreedFailure agree_on_failure(int status = 0, const std::string& error = "",
                               double timeout_seconds = failure_grace_seconds);

// What a runtime of several processes registers (from its own file, CONTACTQP_BUILTIN).
struct ProcessRuntime {
  std::function<int()> rank;   // this process's index while the runtime runs, else −1
  std::function<int()> count;  // the number of processes while it runs, else 0
  std::function<void(const std::map<std::string, std::string>& library_options)> start;
  std::function<void()> connect;  // connect_processes()
  // agree_on_failure() over the processes, while count() > 1.
  std::function<AgreedFailure(int status, const std::string& error, double timeout_seconds)> agree_on_failure;
};
void register_process_runtime(ProcessRuntime runtime);

}  // namespace contactqp
