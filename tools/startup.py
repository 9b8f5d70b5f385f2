#!/usr/bin/python3
"""Start-up of the program and of the Python module, measured as whole processes.

    /usr/bin/python3 tools/startup.py [BUILD] [--runs N]

BUILD is the build folder (default build). For each command: the median wall time of N runs
(default 7) and the shared libraries it initialised (LD_DEBUG=files; for Python, the shared
objects mapped at the end, /proc/self/maps); for the solve, also the median of its wall time
less the total its own report prints (what the report does not count: start-up and exit). The
table of docs/architecture.md, "Plugins".
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

# A 2-DOF QP given as numpy arrays (then scipy is not imported) or as scipy matrices.
QP_SCRIPT = """
import sys
sys.path.insert(0, {python_dir!r})
import numpy, contactqp
{scipy_import}
K, B = numpy.array([[2.0, -1.0], [-1.0, 2.0]]), numpy.array([[1.0, 0.0]])
{scipy_convert}
qp = contactqp.QuadraticProgram(K, numpy.array([1.0, 1.0]), B, numpy.array([0.5]))
assert contactqp.solve(qp, backend="active_set").converged
assert ("scipy" in sys.modules) == {with_scipy}
libraries = set()
for line in open("/proc/self/maps"):
    path = line.split()[-1]
    if ".so" in path:
        libraries.add(path)
print(len(libraries))
"""


def wall(command, runs, expect=0):
    """The median wall time of `runs` runs of `command`, each checked to end with `expect`, and
    the median of its wall time less the total its report printed ("total X" on its last time
    line; None when it prints none)."""
    times, unreported = [], []
    for _ in range(runs):
        start = time.perf_counter()
        done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, check=False)
        seconds = time.perf_counter() - start
        times.append(seconds)
        if done.returncode != expect:
            sys.exit(f"startup: {' '.join(command)} ended {done.returncode}, not {expect}: {done.stderr.decode()}")
        totals = re.findall(r"\btotal ([0-9.]+)", done.stdout.decode())
        if totals:
            unreported.append(seconds - float(totals[-1]))
    return statistics.median(times), statistics.median(unreported) if unreported else None


def program_libraries(command):
    """The shared objects the program initialised (LD_DEBUG=files: one "calling init" each)."""
    env = dict(os.environ, LD_DEBUG="files")
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env, check=False)
    return sum(1 for line in done.stderr.decode().splitlines() if "calling init:" in line)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("build", nargs="?", default="build")
    parser.add_argument("--runs", type=int, default=7)
    args = parser.parse_args()
    program = os.path.join(args.build, "contactqp")
    with tempfile.TemporaryDirectory() as folder:
        bad = os.path.join(folder, "bad.json")
        with open(os.path.join(ROOT, "scenes", "hertz.json")) as source:
            text = source.read()
        with open(bad, "w") as out:
            out.write(text.replace('"body"', '"bodie"', 1))
        rows = [
            ("contactqp --version", [program, "--version"], 0),
            ("contactqp solve (a bad key: exit 2)", [program, "solve", bad], 2),
            ("contactqp solve scenes/hertz.json --backend active_set",
             [program, "solve", os.path.join(ROOT, "scenes", "hertz.json"), "--backend", "active_set", "--json",
              os.path.join(folder, "out.json")], 0),
        ]
        print("| command | median wall [s] | not in its report's total [s] | shared libraries |")
        print("|---|---:|---:|---:|")
        for name, command, expect in rows:
            seconds, unreported = wall(command, args.runs, expect=expect)
            beyond = "" if unreported is None else f"{unreported:.3f}"
            print(f"| `{name}` | {seconds:.3f} | {beyond} | {program_libraries(command)} |")
        python_dir = os.path.abspath(os.path.join(args.build, "python"))
        for with_scipy in (False, True):
            text = QP_SCRIPT.format(python_dir=python_dir, with_scipy=with_scipy,
                                    scipy_import="import scipy.sparse" if with_scipy else "",
                                    scipy_convert="K, B = scipy.sparse.csc_matrix(K), scipy.sparse.csc_matrix(B)"
                                    if with_scipy else "")
            script = [sys.executable, "-c", text]
            mapped = subprocess.run(script, stdout=subprocess.PIPE, check=True).stdout.decode().strip()
            seconds, _ = wall(script, args.runs)
            given = "scipy matrices" if with_scipy else "numpy arrays: no scipy"
            print(f"| `import contactqp` and a 2-DOF QP ({given}) by active_set | {seconds:.3f} | | {mapped} "
                  "(mapped, Python's own included) |")
        alone = f"import sys; sys.path.insert(0, {python_dir!r}); import contactqp"
        seconds, _ = wall([sys.executable, "-c", alone], args.runs)
        print(f"| `import contactqp` alone | {seconds:.3f} | | |")
        seconds, _ = wall([sys.executable, "-c", "import numpy"], args.runs)
        print(f"| `import numpy` alone (what the QP needs besides) | {seconds:.3f} | | |")
        seconds, _ = wall([sys.executable, "-c", "import numpy, scipy.sparse"], args.runs)
        print(f"| `import numpy, scipy.sparse` alone (a QP given as scipy matrices) | {seconds:.3f} | | |")

if __name__ == "__main__":
    main()
