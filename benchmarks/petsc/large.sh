#!/bin/sh
# The ≥ 1e6-DOF 3D run (docs/3d.md, "The sphere at 1.27e6 DOFs"; docs/petsc.md): the shipped
# scenes/hertz-sphere-large.json solved by its default backend, petsc, on 1 and on 2 ranks, each
# rank under /usr/bin/time -v (peak resident memory per rank), with --phase-memory (the peak of
# each phase) and PETSc's -log_view (where the solve's time went); then CHOLMOD's symbolic
# analysis of the same K (factor_prediction): what active_set would need, which does not fit;
# and active_set itself on CHOLMOD (CHOLMOD=0 skips it).
#
#     benchmarks/petsc/large.sh [BUILD_DIR] [OUT_DIR]      (about an hour on 2 cores, 14 GB)
#     RANKS=2 benchmarks/petsc/large.sh                    (only the 2-rank run)
#
# Writes OUT_DIR (default benchmarks/petsc/results/large): ranks1.json, ranks2.json, their
# time-*.txt, phases-*.txt and log-*.txt, and factor-prediction.csv.
set -eu
SOURCE=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-build}
case $BUILD in /*) ;; *) BUILD=$SOURCE/$BUILD ;; esac
OUT=${2:-$SOURCE/benchmarks/petsc/results/large}
mkdir -p "$OUT"
SCENE=$SOURCE/scenes/hertz-sphere-large.json
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cmake -S "$SOURCE" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DCONTACTQP_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$BUILD" -j2 --target contactqp factor_prediction >/dev/null
for RANKS in ${RANKS:-1 2}; do
  # Each rank under its own /usr/bin/time, its file named by the launcher's rank.
  set -- /bin/sh -c 'exec /usr/bin/time -v -o "$0-${OMPI_COMM_WORLD_RANK:-0}.txt" "$@"' "$OUT/time-$RANKS" \
    "$BUILD/contactqp" solve "$SCENE" --json "$OUT/ranks$RANKS.json" --quiet --phase-memory \
    "--petsc-options=-log_view :$OUT/log-$RANKS.txt"
  if [ "$RANKS" -gt 1 ]; then set -- mpirun -n "$RANKS" --oversubscribe "$@"; fi
  "$@" >"$OUT/summary-$RANKS.txt" 2>"$OUT/phases-$RANKS.txt" || true
done
# The direct route on the same scene: active_set on CHOLMOD (refused at the analysis on this
# machine: the factor passes 2^31 entries), and CHOLMOD's prediction of the factor it would need.
if [ "${CHOLMOD:-1}" = 1 ]; then
  /usr/bin/time -v "$BUILD/contactqp" solve "$SCENE" --backend active_set --json "$OUT/active-set-cholmod.json" \
    --quiet --phase-memory >"$OUT/active-set-cholmod-summary.txt" 2>"$OUT/active-set-cholmod-time.txt" || true
fi
"$BUILD/benchmarks/scaling/factor_prediction" --scenes "$SCENE" --out "$OUT"
grep -h "Maximum resident" "$OUT"/time-*.txt
