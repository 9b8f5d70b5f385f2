#!/bin/sh
# Regenerates benchmarks/friction/results (docs/friction-backends.md, "Cost"): builds
# bench_friction and runs it; it prints the figures and writes steps.csv and context.json. A few
# minutes on 2 cores; quote timings from a quiet machine.
#
#     benchmarks/friction/regenerate.sh [BUILD_DIR]        (default: build)
set -eu
SOURCE=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-build}
case $BUILD in /*) ;; *) BUILD=$SOURCE/$BUILD ;; esac
cmake -S "$SOURCE" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DCONTACTQP_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$BUILD" -j2 --target bench_friction
"$BUILD/benchmarks/friction/bench_friction" --out "$SOURCE/benchmarks/friction/results"
