#!/usr/bin/python3
"""ctest entry for a failure on one rank alone under `mpirun -n 2` (docs/petsc.md, "When one rank
fails"): CONTACTQP_TEST_FAULT=1:PHASE:KIND:5 makes rank 1 throw as PHASE begins (read, mesh,
assemble, solve, write) while rank 0 goes on. The run must print that rank's line once, naming
rank 1, end both ranks with the status of the failure (2 bad input, 1 otherwise) within 70 s,
and leave no file: no result, no temporary file. (The 5: the failed rank waits 5 s, not 30, for
a rank stuck in a collective call of the solve.) A small Hertz scene on the petsc backend (the
one whose solve needs both ranks), every output asked for.

usage: check_rank_faults.py CONTACTQP MPIEXEC SCENE PHASE KIND"""
import json
import os
import sys
import tempfile
import time

from checks import MPI_ENV, Checks, run

STATUS = {"input": 2, "error": 1, "memory": 1}
WORDS = {"input": "CONTACTQP_TEST_FAULT", "error": "CONTACTQP_TEST_FAULT", "memory": "out of memory"}


def main(cli, mpiexec, scene_path, phase, kind):
    check = Checks()

    with open(scene_path) as file:
        scene = json.load(file)
    scene["body"]["mesh"] = {"size": 0.2, "contact_size": 0.01}  # a few hundred DOFs: seconds
    with tempfile.TemporaryDirectory() as work:
        path = os.path.join(work, "scene.json")
        with open(path, "w") as file:
            json.dump(scene, file)
        env = dict(MPI_ENV, CONTACTQP_TEST_FAULT="1:%s:%s:5" % (phase, kind))
        command = [mpiexec, "-n", "2", "--oversubscribe", cli, "solve", path, "--backend", "petsc", "--quiet",
                   "--json", os.path.join(work, "out.json"), "--csv", os.path.join(work, "out.csv"),
                   "--vtu", os.path.join(work, "out.pvtu")]
        start = time.monotonic()
        code, out, err = run(command, env, timeout=300)
        seconds = time.monotonic() - start
        left = sorted(os.listdir(work))
    print(err.strip())
    # mpirun may add its own notice of how a rank ended; contactqp's part is one line.
    lines = [line for line in err.splitlines() if line.startswith("contactqp")]
    check(code == STATUS[kind], "exit status %d (expected %d)" % (code, STATUS[kind]))
    check(len(lines) == 1, "one line of contactqp's (%d)" % len(lines))
    check(all(WORDS[kind] in line and "rank 1" in line for line in lines), "the line names the fault and rank 1")
    check(not out.strip(), "nothing on stdout: %r" % out[:200])
    check(seconds <= 70, "ended in %.1f s (at most 70)" % seconds)
    check(left == ["scene.json"], "no file written: %s" % left)
    return 1 if check.failures else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:6]))
