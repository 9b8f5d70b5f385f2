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

// How a run ends on every process at once. Every process passes its exit status and its error
// line (empty when it has none); the lowest-numbered process with a line prints it to stderr,
// once for the run, and the result is the largest status. Collective while the runtime runs on
// several processes. A process that failed waits at most `timeout_seconds` for the others (they
// may be stuck in a collective call it left), then prints its line and ends them all: never a hang.
int agree_on_exit(int status, const std::string& error_line, double timeout_seconds = 60);

// What a runtime of several processes registers (from its own file, CONTACTQP_BUILTIN).
struct ProcessRuntime {
  std::function<int()> rank;   // this process's index while the runtime runs, else −1
  std::function<int()> count;  // the number of processes while it runs, else 0
  std::function<void(const std::map<std::string, std::string>& library_options)> start;
  // agree_on_exit() over the processes, while count() > 1.
  std::function<int(int status, const std::string& error_line, double timeout_seconds)> agree_on_exit;
};
void register_process_runtime(ProcessRuntime runtime);

}  // namespace contactqp
