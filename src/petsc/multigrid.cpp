// set_up_multigrid() and the statistics of its hierarchy (multigrid.hpp).
#include "multigrid.hpp"

#include <mpi.h>

#include <string>
#include <vector>

#include "contactqp/timer.hpp"

namespace contactqp::detail {

const char* const kMultigridOptions[][2] = {
    {"mg_levels_ksp_type", "chebyshev"},    {"mg_levels_pc_type", "jacobi"},
    {"mg_levels_esteig_ksp_type", "cg"},    {"mg_coarse_mg_levels_esteig_ksp_type", "cg"},
    {"pc_gamg_aggressive_coarsening", "2"}, {"mg_coarse_pc_gamg_aggressive_coarsening", "2"},
    {"pc_gamg_coarse_eq_limit", "200"},     {"mg_coarse_pc_gamg_coarse_eq_limit", "200"}};

namespace {

// GAMG as measured best for this code's elasticity matrices (docs/petsc-measurements.md, "GAMG's settings
// (measured)"): threshold 0.02, the smoothers' own eigenvalue estimates (with smoothed
// aggregation's, a coarse operator changed by truncation.hpp kept stale bounds and CG stopped
// with KSP_DIVERGED_INDEFINITE_PC), and from kMultigridOptions the graph squared on the first
// two levels (on the first alone the second level's Galerkin product of a 4-node operator cost
// as much as the first's) and at most 200 equations on the coarsest level (an active-set step
// refactors it: at 1000 that was half of a 7e4-DOF contact loop). Set before PCSetFromOptions:
// options override.
PetscErrorCode configure_gamg(PC pc) {
  PetscFunctionBeginUser;
  PetscCall(PCSetType(pc, PCGAMG));
  PetscReal threshold = 0.02;
  PetscCall(PCGAMGSetThreshold(pc, &threshold, 1));
  PetscCall(PCGAMGSetUseSAEstEig(pc, PETSC_FALSE));
  PetscFunctionReturn(0);
}

double nonzeros(Mat M, MatInfoType type) {
  MatInfo info;
  return MatGetInfo(M, type, &info) ? 0.0 : info.nz_used;
}

// On this rank: a value and a column index per stored entry, a row pointer per row.
double bytes_of(Mat M) {
  MatInfo info;
  PetscInt rows = 0;
  if (MatGetInfo(M, MAT_LOCAL, &info) || MatGetLocalSize(M, &rows, nullptr)) return 0;
  return info.nz_allocated * (sizeof(PetscScalar) + sizeof(PetscInt)) + (rows + 1.0) * sizeof(PetscInt);
}

bool is_multilevel(PC pc) {
  PetscBool yes = PETSC_FALSE;
  PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(pc), &yes, PCMG, PCGAMG, PCML, "");
  return yes;
}

// Sums over the levels of a multilevel PC: rows and nonzeros (global), bytes (this rank).
PetscErrorCode add_levels(PC pc, double* rows, double* entries, double* bytes, int* levels) {
  PetscFunctionBeginUser;
  PetscInt n = 0;
  PetscCall(PCMGGetLevels(pc, &n));
  for (PetscInt level = n - 1; level >= 0; --level) {
    KSP smoother = nullptr;
    Mat op = nullptr;
    PetscCall(PCMGGetSmoother(pc, level, &smoother));
    PetscCall(KSPGetOperators(smoother, nullptr, &op));
    PC inner = nullptr;
    PetscCall(KSPGetPC(smoother, &inner));
    if (level == 0 && inner != pc && is_multilevel(inner)) {
      // A nested AMG on the coarsest level of our PCMG: its levels, its finest being this one.
      PetscCall(add_levels(inner, rows, entries, bytes, levels));
    } else {
      PetscInt M = 0;
      PetscCall(MatGetSize(op, &M, nullptr));
      *rows += M;
      *entries += nonzeros(op, MAT_GLOBAL_SUM);
      *bytes += bytes_of(op);
      ++*levels;
    }
    Mat interpolation = nullptr;
    if (level > 0 && !PCMGGetInterpolation(pc, level, &interpolation) && interpolation)
      *bytes += bytes_of(interpolation);
  }
  PetscFunctionReturn(0);
}

// kMultigridOptions in the options database for the duration of a set-up, each where the
// user's options name nothing of that name: the user's own options win, and the defaults do
// not outlive the set-up (the next solver starts from the user's options alone).
class DefaultOptions {
 public:
  explicit DefaultOptions(const char* prefix) {
    for (const auto& [name, value] : kMultigridOptions) {
      const std::string full = "-" + std::string(prefix ? prefix : "") + name;
      PetscBool given = PETSC_FALSE;
      PetscOptionsHasName(nullptr, nullptr, full.c_str(), &given);
      if (!given && !PetscOptionsSetValue(nullptr, full.c_str(), value)) added_.push_back(full);
    }
  }
  ~DefaultOptions() {
    for (const std::string& name : added_) PetscOptionsClearValue(nullptr, name.c_str());
  }

 private:
  std::vector<std::string> added_;
};

}  // namespace

PC p1_level_preconditioner(PC pc) {
  PetscBool is_mg = PETSC_FALSE;
  PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCMG, &is_mg);
  PetscInt levels = 0;
  if (!is_mg || PCMGGetLevels(pc, &levels) || levels != 2) return nullptr;
  KSP coarse = nullptr;
  PC inner = nullptr;
  if (PCMGGetCoarseSolve(pc, &coarse) || KSPGetPC(coarse, &inner)) return nullptr;
  return inner;
}

PetscErrorCode set_up_multigrid(PC pc, const MultigridData& data, Mat* coarse, MultigridStatistics* statistics) {
  PetscFunctionBeginUser;
  *coarse = nullptr;
  *statistics = MultigridStatistics();
  const char* prefix = nullptr;
  PetscCall(PCGetOptionsPrefix(pc, &prefix));
  PetscBool user_pc = PETSC_FALSE;
  PetscCall(PetscOptionsHasName(nullptr, prefix, "-pc_type", &user_pc));
  const DefaultOptions defaults(prefix);
  Stopwatch clock;
  if (!user_pc && data.coarse_interpolation) {
    // The P1 level: PCMG with two levels, P as its transfer (restriction Pᵀ), PᵀAP computed
    // here once (so that its near-null space can be set before the AMG below is set up).
    Stopwatch galerkin;
    PetscCall(MatPtAP(data.A, data.coarse_interpolation, MAT_INITIAL_MATRIX, 2.0, coarse));
    PetscInt row_block = 1, column_block = 1;
    PetscCall(MatGetBlockSizes(data.coarse_interpolation, &row_block, &column_block));
    if (column_block > 1) MatSetBlockSize(*coarse, column_block);  // dim per vertex; a refusal costs only speed
    PetscCall(MatSetOption(*coarse, MAT_SPD, PETSC_TRUE));
    if (data.coarse_modes) PetscCall(MatSetNearNullSpace(*coarse, data.coarse_modes));
    statistics->galerkin_seconds = galerkin.seconds();
    PetscCall(PCSetType(pc, PCMG));
    PetscCall(PCMGSetLevels(pc, 2, nullptr));
    PetscCall(PCMGSetType(pc, PC_MG_MULTIPLICATIVE));
    PetscCall(PCMGSetGalerkin(pc, PC_MG_GALERKIN_NONE));
    PetscCall(PCMGSetInterpolation(pc, 1, data.coarse_interpolation));
    // One Chebyshev step before and after on the fine level, not two: its matrix-vector
    // products are most of a V-cycle's cost (a P2 row has about 80 entries). On the 1.34e6-DOF
    // sphere one linear solve took 36 CG iterations instead of 27, and 14.6 s instead of 17.4.
    PetscCall(PCMGSetNumberSmooth(pc, 1));
    KSP level = nullptr;
    PetscCall(PCMGGetCoarseSolve(pc, &level));
    PetscCall(KSPSetOperators(level, *coarse, *coarse));
    PetscCall(KSPSetType(level, KSPPREONLY));
    PC amg = nullptr;
    PetscCall(KSPGetPC(level, &amg));
    PetscCall(configure_gamg(amg));
    statistics->method = "mg: P1 level + gamg";
  } else if (!user_pc) {
    PetscCall(configure_gamg(pc));
    statistics->method = "gamg";
  }
  PetscCall(PCSetFromOptions(pc));
  PetscCall(PCSetUp(pc));
  statistics->setup_seconds = clock.seconds();
  if (user_pc || statistics->method.empty()) {
    PCType type = nullptr;
    PetscCall(PCGetType(pc, &type));
    statistics->method = type ? type : "?";
  }
  const double galerkin = statistics->galerkin_seconds, setup = statistics->setup_seconds;
  const std::string method = statistics->method;
  PetscCall(multigrid_statistics(pc, statistics));
  statistics->galerkin_seconds = galerkin;
  statistics->setup_seconds = setup;
  statistics->method = method;
  PetscFunctionReturn(0);
}

PetscErrorCode multigrid_statistics(PC pc, MultigridStatistics* statistics) {
  PetscFunctionBeginUser;
  statistics->levels = 0;
  statistics->grid_complexity = statistics->operator_complexity = statistics->bytes = 0;
  if (!is_multilevel(pc)) PetscFunctionReturn(0);
  Mat A = nullptr;
  PetscCall(PCGetOperators(pc, nullptr, &A));
  PetscInt rows_A = 0;
  PetscCall(MatGetSize(A, &rows_A, nullptr));
  const double entries_A = nonzeros(A, MAT_GLOBAL_SUM);
  double rows = 0, entries = 0, bytes = 0;
  int levels = 0;
  PetscCall(add_levels(pc, &rows, &entries, &bytes, &levels));
  statistics->levels = levels;
  if (rows_A > 0) statistics->grid_complexity = rows / rows_A;
  if (entries_A > 0) statistics->operator_complexity = entries / entries_A;
  statistics->bytes = bytes;
  PetscFunctionReturn(0);
}

}  // namespace contactqp::detail
