#!/bin/sh
# Installs the Debian packages contactqp needs to build, test and benchmark (run as root on
# Debian bookworm). Skips apt entirely when everything is already installed. clang and
# libclang-rt-dev (compiler-rt: libFuzzer and clang's sanitizer runtimes) build CI's sanitizer
# suite and the fuzzers (tools/run-tests.sh, stage 2).
# clang-format (14) checks that the tree is formatted (tools/check-format.sh, a ctest entry).
# pybind11-dev, python3-dev (Python's headers) and python3-pybind11 build the contactqp Python
# module for Debian's /usr/bin/python3; python3-scipy (scipy.sparse in) and python3-pytest run
# its tests. pybind11-dev does not depend on python3-dev, so both are listed. doxygen builds the
# API reference from the public headers (the ctest entry api_reference_builds).
# petsc-dev (PETSc 3.18 with MUMPS and hypre) and OpenMPI: the optional PETSc solver of K
# (docs/linear-solvers.md); the build works without them.
set -eu
packages="cmake g++ make pkg-config
  libeigen3-dev libsuitesparse-dev libopenblas-dev
  coinor-libipopt-dev libnlopt-cxx-dev
  catch2 nlohmann-json3-dev libcli11-dev
  libgmsh-dev gmsh
  petsc-dev openmpi-bin libopenmpi-dev
  clang libclang-rt-dev clang-format
  python3 python3-numpy python3-matplotlib python3-vtk9 python3-getfem
  python3-dev pybind11-dev python3-pybind11 python3-scipy python3-pytest
  doxygen"
missing=""
for p in $packages; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "installing:$missing"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  # shellcheck disable=SC2086
  apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi
