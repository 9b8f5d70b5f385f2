"""What the ctest checks in tests/tools/ share: the environment mpirun needs here (as root, more
ranks than cores), and a list of checks that prints each and keeps the failures."""
import os

MPI_ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")


class Checks:
    """check(condition, text) prints "ok" or "FAIL" and the text; check.failures lists the failed."""

    def __init__(self):
        self.failures = []

    def __call__(self, condition, text):
        print(("ok   " if condition else "FAIL ") + text)
        if not condition:
            self.failures.append(text)
