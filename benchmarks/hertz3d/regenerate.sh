#!/bin/sh
# Regenerates benchmarks/hertz3d/results (docs/3d.md, "Accuracy"): builds bench_hertz3d, runs the
# sphere and punch studies, and draws sphere.png and tables.md. About 10 minutes on 2 cores.
#
#     benchmarks/hertz3d/regenerate.sh [BUILD_DIR]        (default: build)
set -eu
SOURCE=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-build}
case $BUILD in /*) ;; *) BUILD=$SOURCE/$BUILD ;; esac
cmake -S "$SOURCE" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DCONTACTQP_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$BUILD" -j2 --target bench_hertz3d
"$BUILD/benchmarks/hertz3d/bench_hertz3d" --out "$SOURCE/benchmarks/hertz3d/results"
/usr/bin/python3 "$SOURCE/benchmarks/hertz3d/plot.py" "$SOURCE/benchmarks/hertz3d/results"
