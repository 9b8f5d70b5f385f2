#!/bin/sh
# Regenerates everything of docs/tradeoff.md: builds bench_tradeoff, runs the
# GetFEM peer and the tradeoff study on the same meshes, and draws the figures and tables.
#
#     benchmarks/tradeoff/regenerate.sh [BUILD_DIR]        (default: build)
#
# Writes benchmarks/tradeoff/results/: runs.csv, meshes.csv, context.json (bench_tradeoff),
# getfem.csv (benchmarks/peers/getfem_table.py), error_vs_time.png, l2_vs_h.png, time_vs_tol.png
# and tables.md (plot.py). One progress line per run on stderr. Needs what tools/install-deps.sh
# installs (gmsh, python3-getfem and python3-matplotlib for /usr/bin/python3).
set -eu
SOURCE=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-build}
case $BUILD in /*) ;; *) BUILD=$SOURCE/$BUILD ;; esac
RESULTS=$SOURCE/benchmarks/tradeoff/results
PEER=$BUILD/benchmarks/tradeoff/peer
# The meshes: contact element sizes along the arc, far field 50 x (scenes/hertz.json's ratio).
SIZES=0.016,0.008,0.004,0.002,0.001,0.0005
START=$(date +%s)
stamp() { echo "regenerate: $1 ($(( $(date +%s) - START )) s)" >&2; }

stamp "configure and build bench_tradeoff in $BUILD"
cmake -S "$SOURCE" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DCONTACTQP_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$BUILD" -j2 --target bench_tradeoff
mkdir -p "$RESULTS" "$PEER"

stamp "GetFEM on the meshes (integral and nodal contact, 3 solves each)"
/usr/bin/python3 "$SOURCE/benchmarks/peers/getfem_table.py" --study meshes --out-dir "$PEER" \
  --contact-sizes $SIZES --formulations integral,nodal --csv "$RESULTS/getfem.csv" >"$PEER/getfem.md"

stamp "contactqp: every backend x tolerance x mesh"
"$BUILD/benchmarks/tradeoff/bench_tradeoff" --contact-sizes $SIZES --peer-meshes "$PEER" --out "$RESULTS"

stamp "figures and tables"
/usr/bin/python3 "$SOURCE/benchmarks/tradeoff/plot.py" --results "$RESULTS"
stamp "done: $RESULTS"
