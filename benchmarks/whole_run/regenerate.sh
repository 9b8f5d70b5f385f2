#!/bin/sh
# The whole-run benchmark (docs/whole-run.md): `contactqp solve` from process start to exit,
# per phase, against one linear solve of the same K, on the Hertz half disc from 1e3 to 1.1e6
# DOFs (benchmarks/scaling's levels; levels 4-6 with body.mesh.refinements = 2, 7-8 with 3, so
# that Gmsh meshes 1.5e3 to 1.7e4 triangles) and the Hertz sphere (benchmarks/scaling/results-3d's
# levels as Gmsh meshes them, the 4-node one at 1.6e5 DOFs also with refinements = 1, then
# scenes/hertz-sphere-large.json at 1.27e6 DOFs with refinements = 1 on its petsc backend under
# mpirun -n 2, about 6 minutes and 7 GiB per rank). Every run in its own process, one
# after the other, so the ratios of one run are comparable; the machine's other load is not
# controlled (see the page).
#
#     benchmarks/whole_run/regenerate.sh [BUILD_DIR]
set -eu
SOURCE=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-build}
case $BUILD in /*) ;; *) BUILD=$SOURCE/$BUILD ;; esac
OUT=$SOURCE/benchmarks/whole_run/results
mkdir -p "$OUT"
rm -f "$OUT/whole_run.csv"
LEVELS=$SOURCE/benchmarks/scaling/results/scenes
SPHERES=$SOURCE/benchmarks/scaling/results-3d/scenes
RUN="/usr/bin/python3 $SOURCE/benchmarks/whole_run/whole_run.py $BUILD/contactqp $OUT/whole_run.csv"
$RUN --label 2D "$LEVELS/hertz-level-0.json" "$LEVELS/hertz-level-1.json" "$LEVELS/hertz-level-2.json" \
  "$LEVELS/hertz-level-3.json"
$RUN --label 2D --refinements 2 "$LEVELS/hertz-level-4.json" "$LEVELS/hertz-level-5.json" \
  "$LEVELS/hertz-level-6.json"
$RUN --label 2D --refinements 3 "$LEVELS/hertz-level-7.json" "$LEVELS/hertz-level-8.json"
$RUN --label 3D "$SPHERES/sphere-order1-cs0.01.json" "$SPHERES/sphere-order2-cs0.014.json" \
  "$SPHERES/sphere-order2-cs0.01.json" "$SPHERES/sphere-order1-cs0.0035.json"
$RUN --label 3D --refinements 1 "$SPHERES/sphere-order1-cs0.0035.json"
[ -n "${SKIP_LARGE:-}" ] || $RUN --label 3D --refinements 1 --own-backend --ranks 2 "$SOURCE/scenes/hertz-sphere-large.json"
# Before: a contactqp built from the commit before this benchmark (BEFORE=path), on the same
# levels meshed by Gmsh directly, for the before/after table.
if [ -n "${BEFORE:-}" ]; then
  /usr/bin/python3 "$SOURCE/benchmarks/whole_run/whole_run.py" "$BEFORE" "$OUT/whole_run.csv" --label before --before \
    "$LEVELS/hertz-level-5.json" "$LEVELS/hertz-level-8.json"
fi
/usr/bin/python3 "$SOURCE/benchmarks/whole_run/plot.py" "$OUT/whole_run.csv" "$OUT/whole_run.png" "$OUT/whole_run-table.md"
rm -rf "$OUT/runs"
