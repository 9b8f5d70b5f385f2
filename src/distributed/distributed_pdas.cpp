// solve_distributed_pdas() (distributed_pdas.hpp): the distributed bound QP handed to the petsc
// backend's loop (bound_pdas.hpp), with its near-null spaces, and its outcome agreed over the
// ranks (a PETSc error on any rank, bad PETSc options, the memory held).
#include "distributed_pdas.hpp"

#include <mpi.h>
#include <petscksp.h>

#include <algorithm>
#include <mutex>

#include "contactqp/errors.hpp"
#include "petsc/ksp_helpers.hpp"
#include "petsc/petsc_runtime.hpp"

namespace contactqp::detail {
namespace {

// A near-null space of `vectors` (copies, so that the caller's stay its own); orthonormalised
// when asked (GAMG needs orthonormal vectors; the P1 level's modes come without).
PetscErrorCode null_space_of(const std::vector<Vec>& vectors, bool orthonormalise, MatNullSpace* space) {
  *space = nullptr;
  if (vectors.empty()) return 0;
  std::vector<Vec> copies(vectors.size());
  for (std::size_t k = 0; k < vectors.size(); ++k) {
    PetscCall(VecDuplicate(vectors[k], &copies[k]));
    PetscCall(VecCopy(vectors[k], copies[k]));
    if (!orthonormalise) continue;
    for (std::size_t j = 0; j < k; ++j) {
      PetscScalar dot = 0;
      PetscCall(VecDot(copies[k], copies[j], &dot));
      PetscCall(VecAXPY(copies[k], -dot, copies[j]));
    }
    PetscReal norm = 0;
    PetscCall(VecNormalize(copies[k], &norm));
  }
  PetscCall(
      MatNullSpaceCreate(PETSC_COMM_WORLD, PETSC_FALSE, static_cast<PetscInt>(copies.size()), copies.data(), space));
  for (Vec& copy : copies) PetscCall(VecDestroy(&copy));  // the space holds its references
  return 0;
}

// The loop on the distributed problem, with the P1 start for quadratic elements (the P1
// level's columns at a candidate vertex are in its own variables, distributed_problem.hpp).
PetscErrorCode solve(const DistributedBoundQp& problem, const DistributedPdasOptions& options, const WarmStart* start,
                     BoundPdasResult* solved, bool* options_error, double* petsc_bytes) {
  MatNullSpace modes = nullptr, coarse_modes = nullptr;
  PetscCall(null_space_of(problem.near_null_space, false, &modes));  // orthonormal already
  if (modes) PetscCall(MatSetNearNullSpace(problem.A, modes));
  PetscBoundQp qp;
  qp.A = problem.A;
  qp.b = problem.b;
  if (!options.without_bounds) {
    qp.bounded = problem.bounded;
    qp.upper = problem.upper;
  }
  if (problem.coarse_interpolation) {
    PetscCall(null_space_of(problem.coarse_near_null_space, true, &coarse_modes));
    qp.coarse_interpolation = problem.coarse_interpolation;
    qp.coarse_modes = coarse_modes;
    if (!options.without_bounds) qp.coarse_bounded = problem.coarse_bounded;
  }
  BoundPdasOptions settings;
  settings.tol = options.tol;
  settings.max_iterations = options.max_iterations;
  settings.inexact = options.inexact && !options.without_bounds;
  settings.loose_reduction = options.loose_reduction;
  settings.p1_start = options.p1_start && !options.without_bounds;
  // Without bounds nothing but stationarity is left, and the inner rule holds that.
  settings.residual = options.without_bounds ? [](Vec, const std::vector<double>&) { return 0.0; } : options.residual;
  const PetscErrorCode code = solve_bound_pdas(qp, settings, solved, options_error, start);
  if (options.without_bounds) solved->mu.assign(problem.bounded.size(), 0.0);
  *petsc_bytes = matrix_bytes(problem.A) + solved->multigrid.bytes;
  if (modes) PetscCall(MatNullSpaceDestroy(&modes));
  if (coarse_modes) PetscCall(MatNullSpaceDestroy(&coarse_modes));
  return code;
}

}  // namespace

DistributedPdasResult::DistributedPdasResult(DistributedPdasResult&& other) noexcept { *this = std::move(other); }

DistributedPdasResult& DistributedPdasResult::operator=(DistributedPdasResult&& other) noexcept {
  std::swap(status, other.status);
  std::swap(message, other.message);
  std::swap(v, other.v);
  std::swap(mu, other.mu);
  std::swap(iterations, other.iterations);
  std::swap(krylov_iterations, other.krylov_iterations);
  std::swap(linear_solves, other.linear_solves);
  std::swap(preconditioner_setups, other.preconditioner_setups);
  std::swap(active, other.active);
  std::swap(active_bounds, other.active_bounds);
  std::swap(multigrid, other.multigrid);
  std::swap(residual, other.residual);
  std::swap(setup_seconds, other.setup_seconds);
  std::swap(iterate_seconds, other.iterate_seconds);
  std::swap(method, other.method);
  std::swap(matrix_bytes, other.matrix_bytes);
  std::swap(petsc_bytes, other.petsc_bytes);
  std::swap(multigrid_levels, other.multigrid_levels);
  std::swap(grid_complexity, other.grid_complexity);
  std::swap(operator_complexity, other.operator_complexity);
  std::swap(warnings, other.warnings);
  std::swap(solver_of_A, other.solver_of_A);
  return *this;
}

DistributedPdasResult::~DistributedPdasResult() {
  if (v && !petsc_finalized()) VecDestroy(&v);
}

DistributedPdasResult solve_distributed_pdas(const DistributedBoundQp& qp, const DistributedPdasOptions& options,
                                             const DistributedPdasResult* previous) {
  DistributedPdasResult result;
  WarmStart start;
  if (previous) start = {previous->solver_of_A, previous->v, previous->active_bounds, previous->multigrid};
  bool options_error = false;
  {
    std::lock_guard<std::mutex> lock(petsc_mutex());
    PetscRuntime& runtime = PetscRuntime::instance(options.petsc_options);
    runtime.use_options(options.petsc_options);
    const long generation = runtime.generation();
    BoundPdasResult solved;
    double petsc_bytes = 0;
    const PetscErrorCode code = solve(qp, options, previous ? &start : nullptr, &solved, &options_error, &petsc_bytes);
    // A PETSc error on one rank is every rank's (the loop's collectives have ended by then).
    int failed = code != 0;
    MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
    if (failed) {
      result.status = Status::NumericalError;
      result.message = code ? "the PETSc contact solve failed: " + error_text(code)
                            : std::string("the PETSc contact solve failed on another rank");
    } else {
      result.status = solved.status;
      result.message = solved.message;
    }
    std::swap(result.v, solved.v);
    result.mu = solved.mu;
    result.iterations = solved.iterations;
    result.krylov_iterations = solved.krylov_iterations;
    result.linear_solves = solved.linear_solves;
    result.preconditioner_setups = solved.preconditioner_setups;
    result.active = solved.active;
    result.active_bounds = solved.active_bounds;
    result.multigrid = solved.multigrid;
    result.residual = solved.residual;
    result.setup_seconds = solved.setup_seconds;
    result.iterate_seconds = solved.iterate_seconds;
    result.method = solved.method;
    result.solver_of_A = solved.solver_of_A;
    result.multigrid_levels = solved.multigrid.levels;
    result.grid_complexity = solved.multigrid.grid_complexity;
    result.operator_complexity = solved.multigrid.operator_complexity;
    double mine[2] = {matrix_bytes(qp.A), petsc_bytes};
    MPI_Allreduce(MPI_IN_PLACE, mine, 2, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
    result.matrix_bytes = mine[0];
    result.petsc_bytes = mine[1];
    if (runtime.generation() == generation)
      for (const std::string& option : runtime.unused(options.petsc_options))
        result.warnings.push_back("PETSc option " + option + " was not used (PETSc's -options_left)");
  }
  int any_options_error = options_error;
  MPI_Allreduce(MPI_IN_PLACE, &any_options_error, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  if (any_options_error) throw InputError("petsc_options", "= \"" + options.petsc_options + "\": " + result.message);
  return result;
}

}  // namespace contactqp::detail
