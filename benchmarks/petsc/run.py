#!/usr/bin/python3
"""The petsc backend against active_set on CHOLMOD (docs/petsc.md): time and peak memory per
rank on Hertz's problem, 2D (scenes/hertz.json refined) and 3D (scenes/hertz-sphere.json with
4-node tetrahedra, refined at the contact), for

  active_set (CHOLMOD)      contactqp solve --backend active_set
  one solve (CHOLMOD)       contactqp solve --no-contact
  petsc, 1 and 2 ranks      [mpirun -n 2] contactqp solve --backend petsc [--petsc-options BEST]
  one solve (PETSc KSP)     [mpirun -n 2] contactqp solve --no-contact --linear-solver petsc
  one solve (petsc run)     [mpirun -n 2] contactqp solve --no-contact --backend petsc

each run wrapped in /usr/bin/time (wall seconds, peak resident set per rank). Writes
OUT/petsc.csv and the level scenes in OUT/scenes.

usage: benchmarks/petsc/run.py BUILD_DIR OUT_DIR LEVEL...   (LEVEL: 2d:SIZE:CONTACT_SIZE or 3d:CONTACT_SIZE)
environment: BEST="-pc_gamg_..." (the best options found), CAP_GB (ulimit -v per run, default 6)"""
import csv
import json
import os
import re
import subprocess
import sys

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BEST = os.environ.get("BEST", "-pc_gamg_reuse_interpolation true -pc_gamg_use_sa_esteig false")
CAP_KB = int(float(os.environ.get("CAP_GB", "6")) * 1024 * 1024)
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def level_scene(level, out):
    parts = level.split(":")
    if parts[0] == "2d":
        scene = json.load(open(os.path.join(SOURCE, "scenes/hertz.json")))
        scene["body"]["mesh"]["size"] = float(parts[1])
        scene["body"]["mesh"]["contact_size"] = float(parts[2])
        name = "hertz-size%s-cs%s.json" % (parts[1], parts[2])
    else:
        scene = json.load(open(os.path.join(SOURCE, "scenes/hertz-sphere.json")))
        scene["body"]["mesh"]["order"] = 1
        scene["body"]["mesh"]["contact_size"] = float(parts[1])
        name = "sphere-order1-cs%s.json" % parts[1]
    scene["description"] = "benchmarks/petsc/run.py level " + level
    os.makedirs(os.path.join(out, "scenes"), exist_ok=True)
    path = os.path.join(out, "scenes", name)
    json.dump(scene, open(path, "w"), indent=2)
    return path


def run(cli, scene, ranks, arguments, out):
    """One run: its JSON, wall seconds and each rank's peak resident set (MiB)."""
    result = os.path.join(out, "last.json")
    times = os.path.join(out, "time.%d")
    if os.path.exists(result):
        os.remove(result)
    # Each rank under its own /usr/bin/time; %p would need a shell: the rank from the launcher.
    inner = ["/bin/sh", "-c",
             'ulimit -v %d; exec /usr/bin/time -f "%%e %%M" -o "%s.${OMPI_COMM_WORLD_RANK:-0}" "$@"' % (CAP_KB, times[:-3]),
             "sh", cli, "solve", scene, "--json", result] + arguments
    # --verbose: the petsc backend's message then carries its resident growth per rank.
    inner.append("--verbose")
    command = (["mpirun", "-n", str(ranks), "--oversubscribe"] if ranks > 1 else []) + inner
    done = subprocess.run(command, env=ENV, capture_output=True, text=True)
    walls, peaks = [], []
    for rank in range(ranks):
        try:
            wall, peak = open(times % rank).read().split()[-2:]
            walls.append(float(wall))
            peaks.append(float(peak) / 1024)
        except (OSError, ValueError):
            pass
    report = json.load(open(result)) if os.path.exists(result) else {}
    return report, max(walls) if walls else None, peaks, done.returncode, done.stderr.strip()[-300:]


def main(build, out, levels):
    cli = os.path.join(os.path.abspath(build), "contactqp")
    os.makedirs(out, exist_ok=True)
    rows = []
    configs = [
        ("active_set", "cholmod", 1, ["--backend", "active_set"]),
        ("one solve", "cholmod", 1, ["--no-contact"]),
        ("petsc", "default", 1, ["--backend", "petsc"]),
        ("petsc", "default", 2, ["--backend", "petsc"]),
        ("petsc", "best", 1, ["--backend", "petsc", "--petsc-options=" + BEST]),
        ("petsc", "best", 2, ["--backend", "petsc", "--petsc-options=" + BEST]),
        ("one solve", "petsc", 1, ["--no-contact", "--linear-solver", "petsc"]),
        ("one solve", "petsc", 2, ["--no-contact", "--linear-solver", "petsc"]),
        # The petsc backend's own reference: the same distributed run, KSP and hierarchy, no rows.
        ("one solve", "petsc backend", 1, ["--backend", "petsc", "--no-contact"]),
        ("one solve", "petsc backend", 2, ["--backend", "petsc", "--no-contact"]),
    ]
    for level in levels:
        scene = level_scene(level, out)
        for backend, options, ranks, arguments in configs:
            report, wall, peaks, code, err = run(cli, scene, ranks, arguments, out)
            t = report.get("timings", {})
            message = report.get("message", "")
            memory = re.search(r"A ([0-9.e+-]+) MiB per rank; PETSc memory per rank ([0-9.e+-]+) MiB", message)
            krylov = re.search(r"([0-9]+) Krylov iterations", message)
            row = {
                "level": level, "dofs": report.get("dofs"), "constraints": report.get("constraints"),
                "backend": backend, "options": options, "ranks": ranks, "status": report.get("status", "exit %d" % code),
                "iterations": report.get("iterations"),
                "solver_seconds": round(sum(t.get(k, 0) for k in ("transform", "factorize", "solve")), 4) if t else None,
                "total_seconds": round(t.get("total", 0), 3) if t else None, "wall_seconds": wall,
                "peak_mib_per_rank": round(max(peaks), 1) if peaks else None,
                "petsc_mib_per_rank": float(memory.group(2)) if memory else None,
                "matrix_mib_per_rank": float(memory.group(1)) if memory else None,
                "krylov_iterations": int(krylov.group(1)) if krylov else None,
                "message": message or err,
            }
            print(json.dumps(row), flush=True)
            rows.append(row)
            with open(os.path.join(out, "petsc.csv"), "w", newline="") as file:
                writer = csv.DictWriter(file, fieldnames=list(rows[0].keys()))
                writer.writeheader()
                writer.writerows(rows)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], sys.argv[3:])
