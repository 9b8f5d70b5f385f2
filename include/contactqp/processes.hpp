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
// command line it starts with. A library whose calls need it running calls it first: where
// PETSc is built in, Ipopt's MUMPS resolves to PETSc's MPI build, which aborts without MPI.
void start_process_runtime(const std::map<std::string, std::string>& library_options = {});

// Connects the processes launched together (MPI alone, no library on it yet), once per process,
// if a runtime is built in; nothing otherwise. main() calls it first when the launcher says there
// are several, so that every failure, even in reading the scene, is agreed at the next phase
// boundary (run/phases.hpp). start_process_runtime() later finds the connection and uses it.
void connect_processes();

// How a run ends on every process at once. Every process passes its exit status and its error
// line (empty when it has none); the lowest-numbered process with a line prints it to stderr,
// once for the run (naming its process when not every process failed), and the result is the largest status. Collective while the runtime runs on
// several processes. A process that failed waits at most `timeout_seconds` for the others (they
// may be stuck in a collective call it left), then prints its line and ends them all: never a hang.
// 30 s: long enough for the others to reach a boundary from any phase of a large run's step,
// short enough that a run stuck in a collective ends well within a minute.
constexpr double failure_grace_seconds = 30;
int agree_on_exit(int status, const std::string& error_line, double timeout_seconds = failure_grace_seconds);

// What a runtime of several processes registers (from its own file, CONTACTQP_BUILTIN).
struct ProcessRuntime {
  std::function<int()> rank;   // this process's index while the runtime runs, else −1
  std::function<int()> count;  // the number of processes while it runs, else 0
  std::function<void(const std::map<std::string, std::string>& library_options)> start;
  std::function<void()> connect;  // connect_processes()
  // agree_on_exit() over the processes, while count() > 1.
  std::function<int(int status, const std::string& error_line, double timeout_seconds)> agree_on_exit;
};
void register_process_runtime(ProcessRuntime runtime);

}  // namespace contactqp
