"""What the ctest checks in tests/tools/ share: the environment mpirun needs here (as root, more
ranks than cores), a way to run a command that survives Open MPI's known teardown race, and a
list of checks that prints each and keeps the failures."""
import os
import signal
import subprocess
import sys

MPI_ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")

# Open MPI 4.1's mpirun (Debian bookworm: 4.1.4 with PMIx 4.2) now and then dies of SIGPIPE after
# its ranks have finished and written everything: its PMIx server answers a rank that has
# already closed its socket (open-mpi/ompi#11322, openpmix/openpmix#1863). It has failed one CI
# run so far (`mpirun -n 2` ended by signal 13, its outputs complete, stderr empty).
# Two defences, both confined to the launcher: mpirun inherits SIGPIPE ignored (Python's
# subprocess otherwise restores the default action, which kills the process; ignored, the
# write fails with EPIPE, which PMIx handles, and Open MPI resets the ranks' handlers itself),
# and a launcher that still ends by SIGPIPE is run once more, with a note. A rank's own death
# by a signal is reported by mpirun as an exit status, never as mpirun's signal: it is not
# retried.
LAUNCHER_NAMES = ("mpirun", "mpiexec", "orterun")


def is_launcher(command):
    return os.path.basename(command[0]).split(".")[0] in LAUNCHER_NAMES


def run(command, env, timeout=900, capture=True):
    """(exit status, stdout, stderr) of the command (None, None without capture: the output passes
    through); an MPI launcher is run as said above."""
    launcher = is_launcher(command)
    for attempt in (1, 2):
        done = subprocess.run(command, env=env, capture_output=capture, text=True, timeout=timeout,
                              restore_signals=not launcher)
        if launcher and done.returncode == -signal.SIGPIPE and attempt == 1:
            print("note: %s ended by SIGPIPE at teardown (Open MPI's known race); run once more" % command[0],
                  file=sys.stderr, flush=True)
            continue
        return done.returncode, done.stdout, done.stderr


class Checks:
    """check(condition, text) prints "ok" or "FAIL" and the text; check.failures lists the failed."""

    def __init__(self):
        self.failures = []

    def __call__(self, condition, text):
        print(("ok   " if condition else "FAIL ") + text)
        if not condition:
            self.failures.append(text)
