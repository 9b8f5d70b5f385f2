#!/bin/sh
# Where the direct solver stops fitting in 3D (docs/3d.md, "Where the time and memory go"):
# Hertz's sphere (scenes/hertz-sphere.json) refined past the sizes this machine can factorise,
# and CHOLMOD's symbolic analysis of K alone (METIS, the 3D default): nnz(L), the bytes
# factorising would allocate, the flops. No factorisation runs, so this needs only the memory of
# the mesh and K (a few GB at 1e6 DOFs).
#
#     benchmarks/scaling/factor-prediction-3d.sh [BUILD_DIR]
#     LEVELS="1:0.0035 2:0.007" benchmarks/scaling/factor-prediction-3d.sh    (order:contact_size)
#
# Writes benchmarks/scaling/results-3d/: prediction-scenes/ (the levels), factor-prediction.csv.
set -eu
SOURCE=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-build}
case $BUILD in /*) ;; *) BUILD=$SOURCE/$BUILD ;; esac
RESULTS=$SOURCE/benchmarks/scaling/results-3d
mkdir -p "$RESULTS/prediction-scenes"
cmake -S "$SOURCE" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DCONTACTQP_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$BUILD" -j2 --target factor_prediction
LEVELS=${LEVELS:-"1:0.0035 2:0.007 1:0.0025 2:0.005 1:0.0018 2:0.0035"}
. "$SOURCE/benchmarks/scaling/sphere-levels.sh"
sphere_levels "$SOURCE" "$RESULTS/prediction-scenes" "$LEVELS" benchmarks/scaling/factor-prediction-3d.sh
cd "$SOURCE"
"$BUILD/benchmarks/scaling/factor_prediction" --scenes "$SCENES" --out "$RESULTS"
