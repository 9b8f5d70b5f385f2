#!/bin/sh
# The installed package as another project sees it: `cmake --install` into a fresh prefix, then
# examples/downstream built with find_package(contactqp) and run, the same source built through
# pkg-config, the installed CLI run on a scene, and the installed Python module imported.
# Usage: check_install.sh BUILD_DIR SOURCE_DIR SCRATCH_DIR [PYTHON_DIR relative to the prefix]
set -eu
build=$1 source=$2 scratch=$3 python_dir=${4:-}
rm -rf "$scratch"
mkdir -p "$scratch"
prefix=$scratch/prefix
cmake --install "$build" --prefix "$prefix" >"$scratch/install.log"

cmake -S "$source/examples/downstream" -B "$scratch/downstream" -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_BUILD_TYPE=Release >"$scratch/configure.log"
cmake --build "$scratch/downstream" >"$scratch/build.log"
"$scratch/downstream/downstream"

# shellcheck disable=SC2046
g++ -std=c++17 -O1 "$source/examples/downstream/main.cpp" -o "$scratch/downstream_pc" \
  $(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --cflags --libs contactqp)
"$scratch/downstream_pc" >/dev/null
echo "pkg-config build: ok"

"$prefix/bin/contactqp" solve "$source/scenes/hertz.json" --backend active_set >/dev/null
echo "installed CLI: ok"

if [ -n "$python_dir" ]; then
  PYTHONPATH="$prefix/$python_dir" /usr/bin/python3 -c "
import contactqp, sys
assert contactqp.__file__.startswith('$prefix/'), contactqp.__file__
print('installed Python module:', contactqp.__version__, contactqp.__file__)"
fi
