#!/bin/sh
# The 3D scaling study (docs/3d.md, "Where the time and memory go"): Hertz's sphere
# (scenes/hertz-sphere.json) refined from about 1e4 DOFs upwards, with 4-node and 10-node
# tetrahedra, every backend against one linear solve of the same K in the same process
# (scaling_benchmark --scenes), METIS ordering (the 3D default).
#
#     benchmarks/scaling/regenerate-3d.sh [BUILD_DIR] [TIME_CAP_SECONDS]     (defaults: build, 300)
#     LEVELS="1:0.01 2:0.02" benchmarks/scaling/regenerate-3d.sh             (only these order:contact_size levels)
#
# Writes benchmarks/scaling/results-3d/: scenes/ (the levels), scaling.csv, context.json. A
# backend slower than the cap on one level is skipped on the larger ones and recorded as such.
set -eu
SOURCE=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-build}
CAP=${2:-300}
case $BUILD in /*) ;; *) BUILD=$SOURCE/$BUILD ;; esac
RESULTS=$SOURCE/benchmarks/scaling/results-3d
mkdir -p "$RESULTS/scenes"
cmake -S "$SOURCE" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DCONTACTQP_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$BUILD" -j2 --target scaling_benchmark
# order:contact_size, from about 1e4 DOFs up; the largest 4-node level has about 4e5 DOFs.
LEVELS=${LEVELS:-"1:0.01 2:0.02 1:0.007 2:0.014 1:0.005 2:0.01 1:0.0035 2:0.007 1:0.0025"}
. "$SOURCE/benchmarks/scaling/sphere-levels.sh"
sphere_levels "$SOURCE" "$RESULTS/scenes" "$LEVELS" benchmarks/scaling/regenerate-3d.sh
"$BUILD/benchmarks/scaling/scaling_benchmark" --scenes "$SCENES" --out "$RESULTS" --time-cap "$CAP"
