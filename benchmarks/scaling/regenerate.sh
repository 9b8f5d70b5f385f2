#!/bin/sh
# Regenerates everything of docs/scaling.md: builds the two benchmark executables, runs every
# backend on the Hertz levels (1e3 to 1.1e6 DOFs) against one linear solve in the same process,
# then the ordering study, and draws the figure and the tables.
#
#     benchmarks/scaling/regenerate.sh [BUILD_DIR]        (default: build)
#
# Writes benchmarks/scaling/results/: scaling.csv, context.json, scenes/ (scaling_benchmark),
# orderings.csv, orderings-context.json (ordering_benchmark), scaling.png and scaling-table.md
# (plot.py). A backend that exceeds the time cap (300 s per solve) is skipped on the larger
# meshes and recorded as such. About 30 minutes on a 2-core machine; peak memory about 4 GB.
set -eu
SOURCE=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-build}
case $BUILD in /*) ;; *) BUILD=$SOURCE/$BUILD ;; esac
RESULTS=$SOURCE/benchmarks/scaling/results
START=$(date +%s)
stamp() { echo "regenerate: $1 ($(( $(date +%s) - START )) s)" >&2; }

stamp "configure and build the scaling benchmarks in $BUILD"
cmake -S "$SOURCE" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DCONTACTQP_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$BUILD" -j2 --target scaling_benchmark ordering_benchmark

stamp "every backend on every level"
"$BUILD/benchmarks/scaling/scaling_benchmark" --levels all --out "$RESULTS"

stamp "orderings (AMD, METIS, CHOLMOD's choice) on the four largest levels"
"$BUILD/benchmarks/scaling/ordering_benchmark" --out "$RESULTS"

stamp "figure and tables"
/usr/bin/python3 "$SOURCE/benchmarks/scaling/plot.py" "$RESULTS"
stamp "done: $RESULTS"
