#!/bin/sh
# The petsc backend's method against TAO's bound-constrained methods on the same bound form
# (docs/petsc-measurements.md, "pdas against TAO"): one line per scene and method with status, outer and
# Krylov iterations and the backend's seconds (factorize + solve), all in one run so that the
# ratios compare on a shared machine.
#
#     benchmarks/petsc/methods.sh [BUILD_DIR] [SCENE...]
set -eu
SOURCE=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$SOURCE/build}
[ $# -gt 0 ] && shift
SCENES=${*:-"$SOURCE/scenes/hertz.json $SOURCE/scenes/disc-in-vgroove.json"}
for scene in $SCENES; do
  for method in "pdas|" "pdas|-pc_gamg_reuse_interpolation true -pc_gamg_use_sa_esteig false" "tao|" \
                "tao|-tao_type bqnls" "tao|-tao_type bntr" "tao|-tao_type gpcg"; do
    name=${method%%|*}
    options=${method#*|}
    line=$("$BUILD/contactqp" solve "$scene" --backend petsc --tol 1e-10 --max-iterations 2000 \
             --backend-option method="$name" --petsc-options="$options -options_left 0" 2>&1 |
           grep -E "status|time \[s\]" | tr -s ' ' | tr '\n' ' ')
    echo "$(basename "$scene") | $name $options | $line"
  done
done
