// process_rank(), process_count() and agree_on_exit() (processes.hpp): the launcher's
// environment before MPI starts, MPI itself (through petsc_solver.hpp) once it runs.
#include "contactqp/processes.hpp"

#include <cstdlib>
#include <iostream>
#include <string>

#include "petsc_solver.hpp"

namespace contactqp {
namespace {

// The launcher's value of one of `names` (OpenMPI, PMIx, MPICH's PMI), or -1.
int launcher_value(std::initializer_list<const char*> names) {
  for (const char* name : names)
    if (const char* text = std::getenv(name)) {
      char* end = nullptr;
      const long value = std::strtol(text, &end, 10);
      if (end != text && *end == '\0' && value >= 0) return static_cast<int>(value);
    }
  return -1;
}

}  // namespace

int process_rank() {
  const int rank = detail::mpi_rank();
  if (rank >= 0) return rank;
  const int launched = launcher_value({"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"});
  return launched >= 0 ? launched : 0;
}

int process_count() {
  const int size = detail::mpi_size();
  if (size >= 1) return size;
  const int launched = launcher_value({"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"});
  return launched >= 1 ? launched : 1;
}

void sum_over_ranks(double* values, long n) {
  if (detail::mpi_size() > 1) detail::mpi_sum(values, n);
}

int agree_on_exit(int status, const std::string& error_line, double timeout_seconds) {
  if (detail::mpi_size() > 1) return detail::mpi_agree_on_exit(status, error_line, timeout_seconds);
  // No MPI between the processes (a failure before PETSc started, the same on every rank):
  // each decides alone, and only rank 0 speaks.
  if (!error_line.empty() && process_rank() == 0) std::cerr << error_line << "\n";
  return status;
}

}  // namespace contactqp
