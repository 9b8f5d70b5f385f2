#!/usr/bin/python3
"""ctest entries that start an MPI launcher themselves go through this: MPIEXEC ARGS... run as
tests/tools/checks.py runs a launcher (SIGPIPE ignored, once more after Open MPI's teardown
race), the output passed through, the launcher's exit status returned.

usage: run_mpi.py MPIEXEC ARGS..."""
import sys

from checks import MPI_ENV, run

if __name__ == "__main__":
    code = run(sys.argv[1:], MPI_ENV, timeout=None, capture=False)[0]
    # A signal's death as a shell reports it (128 + the signal), not Python's negative status.
    sys.exit(128 - code if code < 0 else code)
