"""What the ctest checks in tests/tools/ share: the environment mpirun needs here (as root, more
ranks than cores), a way to run a command that survives Open MPI's known teardown race and
LeakSanitizer's tracer crash, and a list of checks that prints each and keeps the failures."""
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

# The sanitizer build's own runtime fault (tools/run-tests.sh reruns a ctest entry whose log shows
# it): LeakSanitizer's tracer, scanning the threads at exit for its leak check, sometimes dies of
# SIGSEGV ("Tracer caught signal 11") and the process aborts, after the program has done and
# written everything. Under mpirun it hits rank 0 of `mpirun -n 2` on a scene refused at its
# load steps (exit 2 after the ranks agreed on the failure, tests/tools/check_mpirun.py): in 11
# of 52 runs of CI's sanitizer build here, with or without the progress line's thread (and in 5
# of 20 with ASan's fake stacks off); while scanning the main thread's thread-local storage, since
# LSAN_OPTIONS=use_tls=0 made 20 of 20 runs end without it (and reported allocations that only
# TLS holds, glibc's dlopen scope and libgomp's, as leaks). dlclose() is already a no-op there
# (tools/sanitizer/keep_libraries_loaded.cpp); the cause inside the sanitizer's runtime is not
# found. The checks capture the ranks' stderr, so ctest's log never shows the line run-tests.sh
# looks for: a command whose stderr has it runs again here, with a note, up to three times more.
# A leak the scan finds is "ERROR: LeakSanitizer: detected memory leaks": never retried.
LSAN_TRACER_CRASH = "LeakSanitizer has encountered a fatal error"


def remove_stale(*paths):
    """Removes earlier runs' outputs, so that a check reads only what this run wrote."""
    for path in paths:
        if os.path.exists(path):
            os.remove(path)


def is_launcher(command):
    return os.path.basename(command[0]).split(".")[0] in LAUNCHER_NAMES


def run(command, env, timeout=900, capture=True):
    """(exit status, stdout, stderr) of the command (None, None without capture: the output passes
    through); an MPI launcher is run as said above."""
    launcher = is_launcher(command)
    pipe_retries, tracer_retries = 1, 3
    while True:
        done = subprocess.run(command, env=env, capture_output=capture, text=True, timeout=timeout,
                              restore_signals=not launcher)
        if launcher and done.returncode == -signal.SIGPIPE and pipe_retries > 0:
            pipe_retries -= 1
            print("note: %s ended by SIGPIPE at teardown (Open MPI's known race); run once more" % command[0],
                  file=sys.stderr, flush=True)
            continue
        if capture and LSAN_TRACER_CRASH in (done.stderr or "") and tracer_retries > 0:
            tracer_retries -= 1
            print("note: %s: LeakSanitizer's tracer crashed at exit (the sanitizer runtime's fault, not a finding); "
                  "run once more" % os.path.basename(command[0]), file=sys.stderr, flush=True)
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
