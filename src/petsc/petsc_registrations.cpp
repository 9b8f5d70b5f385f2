// What the PETSc room registers besides the petsc backend (petsc_backend.cpp) and the problem
// held in parts (in_parts.cpp): the runtime of several processes, the PETSc solver of K and the
// distributed run. Built where PETSc is, into the room linked whole (cqp_petsc: the tests, the
// benchmarks, the PETSc plugin) and into the program's calls to the plugin
// (cqp_petsc_plugin_calls), whose definitions of the same functions open the plugin.
#include "contactqp/linear_solver.hpp"
#include "contactqp/processes.hpp"
#include "distributed/run_distributed.hpp"
#include "mpi.hpp"
#include "petsc_solver.hpp"
#include "qp/builtins.hpp"
#include "run/distributed_run.hpp"

// Which process this is and how the processes end together, once PETSc has started MPI; and
// how to start it, with the user's PETSc options on PETSc's command line.
CONTACTQP_BUILTIN(mpi_processes) {
  ProcessRuntime mpi;
  mpi.rank = mpi_rank;
  mpi.count = mpi_size;
  mpi.start = start_petsc_runtime;
  mpi.connect = connect_mpi;
  mpi.agree_on_failure = mpi_agree_on_failure;
  register_process_runtime(mpi);
}

// --linear-solver petsc: make_linear_solver() finds this factory (linear_solver.hpp).
CONTACTQP_BUILTIN(petsc_solver) {
  register_linear_solver(LinearSolverKind::Petsc,
                         [](const Eigen::SparseMatrix<double>& A, const LinearSolverOptions& options) {
                           return make_petsc_solver(A, options);
                         });
}

// run_scene() goes this way for the petsc backend under mpirun (run/distributed_run.hpp).
CONTACTQP_BUILTIN(distributed_run) {
  DistributedRun run;
  run.takes = takes_distributed_run;
  run.run = run_distributed;
  register_distributed_run(run);
}
