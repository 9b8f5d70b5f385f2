#!/usr/bin/python3
"""The whole run of `contactqp solve` per phase against one linear solve of the same K.

    /usr/bin/python3 benchmarks/whole_run/whole_run.py CONTACTQP OUT.csv SCENE.json... \
        [--label TEXT] [--refinements N] [--before] [--own-backend --ranks N]

Each scene is solved twice, each in its own process: with contact (backend active_set, writing
the result JSON, the profile CSV and the ParaView file, as a user would; --phase-memory for the
peak memory of each phase) and with --no-contact (one factorisation and solve of the same K,
the unit of cost). Both run under /usr/bin/time -v, so "wall" is the process from start to exit
and "max_rss_mib" its peak resident memory. The phases come from the result JSON's timings.
--refinements N sets body.mesh.refinements = N in each half-disc or hemisphere scene (a copy under
runs/ beside OUT.csv). --before: a contactqp from before --quiet, --phase-memory and the
write phase (for the before/after table). --own-backend: the scene's own backend (the 3D scene
at 1.27e6 DOFs, whose direct factor does not fit: petsc), under `mpirun -n N` with --ranks N;
there one linear solve of K is the certificate's (the certificate solves with K once, its GAMG
set-up included, on the same ranks), so no --no-contact run. Rows are appended to OUT.csv.
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys

# The result JSON's phases; the backend's "solve" is its work after the factorisation
# (for active_set: condense + iterate + recover).
PHASES = ["mesh", "model", "assemble", "factorize", "solve", "certify", "postprocess", "write"]

COLUMNS = (["label", "scene", "dofs", "iterations"] + PHASES +
           ["contact_solve", "total_in_process", "wall", "max_rss_mib", "linear_solve", "linear_wall",
            "linear_max_rss_mib", "wall_over_linear_solve", "mesh_assemble_over_solve", "hertz_error_half_width",
            "hertz_error_contact_radius", "hertz_error_max_pressure", "hertz_error_l2"] +
           ["peak_mib_" + p for p in ("mesh", "assemble", "solve", "certify", "postprocess", "write")])


def timed_run(command):
    """Runs `command` under /usr/bin/time -v; returns (exit status, wall seconds, peak RSS MiB, stdout)."""
    completed = subprocess.run(["/usr/bin/time", "-v"] + command, capture_output=True, text=True)
    wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (\S+)", completed.stderr).group(1)
    seconds = 0.0
    for part in wall.split(":"):
        seconds = 60 * seconds + float(part)
    rss_kb = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", completed.stderr).group(1))
    return completed.returncode, seconds, rss_kb / 1024.0, completed.stdout, completed.stderr


def mpirun(ranks):
    """The launcher for `ranks` processes (none for one); OpenMPI refuses root without the two variables."""
    if ranks <= 1:
        return []
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    return ["mpirun", "-n", str(ranks), "--oversubscribe"]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("contactqp")
    parser.add_argument("out")
    parser.add_argument("scenes", nargs="+")
    parser.add_argument("--refinements", type=int, default=0)
    parser.add_argument("--label", default="")
    parser.add_argument("--own-backend", action="store_true",
                        help="the scene's backend, linear solve = the certificate's (see the docstring)")
    parser.add_argument("--ranks", type=int, default=1, help="with --own-backend: processes under mpirun")
    parser.add_argument("--before", action="store_true",
                        help="a contactqp from before --quiet and the write phase (the before/after table)")
    arguments = parser.parse_args()
    out_dir = os.path.dirname(os.path.abspath(arguments.out))
    work = os.path.join(out_dir, "runs")
    os.makedirs(work, exist_ok=True)
    quiet = [] if arguments.before else ["--quiet"]
    rows = []
    for scene_path in arguments.scenes:
        scene = json.load(open(scene_path))
        name = os.path.splitext(os.path.basename(scene_path))[0]
        if arguments.refinements and scene["body"]["shape"] in ("half_disc", "hemisphere"):
            scene["body"]["mesh"]["refinements"] = arguments.refinements
            name += "-r%d" % arguments.refinements
            scene_path = os.path.join(work, name + ".json")
            json.dump(scene, open(scene_path, "w"), indent=1)
        result = os.path.join(work, name + "-result.json")
        linear = os.path.join(work, name + "-linear.json")
        backend = [] if arguments.own_backend else ["--backend", "active_set"]
        status, wall, rss, stdout, stderr = timed_run(
            mpirun(arguments.ranks) + [arguments.contactqp, "solve", scene_path] + backend + ["--json", result,
             "--csv", os.path.join(work, name + ".csv"), "--vtu", os.path.join(work, name + ".vtu")] + quiet + ([] if arguments.before else ["--phase-memory"]))
        if status != 0:
            sys.exit("%s: exit %d\n%s" % (scene_path, status, stderr))
        report = json.load(open(result))
        timings = report["timings"]
        if arguments.own_backend:
            linear_seconds, linear_wall, linear_rss = timings["certify"], "", 0.0
        else:
            linear_status, linear_wall, linear_rss, _, linear_stderr = timed_run(
                [arguments.contactqp, "solve", scene_path, "--no-contact", "--json", linear] + quiet)
            if linear_status not in (0, 1):
                sys.exit("%s --no-contact: exit %d\n%s" % (scene_path, linear_status, linear_stderr))
            linear_report = json.load(open(linear))
            linear_seconds = linear_report["timings"].get("factorize", 0) + linear_report["timings"].get("solve", 0)
        row = {"label": arguments.label, "scene": name, "dofs": report["dofs"], "iterations": report["iterations"]}
        for phase in PHASES:
            row[phase] = timings.get(phase, 0.0)
        # The petsc backend also times its "transform" (the bound form: scaling, change of variables).
        row["contact_solve"] = row["factorize"] + row["solve"] + timings.get("transform", 0.0)
        row["total_in_process"] = timings.get("total", 0.0)
        row["wall"] = wall
        row["max_rss_mib"] = round(rss, 1)
        row["linear_solve"] = linear_seconds
        row["linear_wall"] = linear_wall
        row["linear_max_rss_mib"] = round(linear_rss, 1)
        row["wall_over_linear_solve"] = wall / linear_seconds if linear_seconds > 0 else ""
        row["mesh_assemble_over_solve"] = (row["mesh"] + row["model"] + row["assemble"]) / row["contact_solve"]
        peaks = re.search(r"peak memory \[MiB\]: (.*)", stderr)
        if peaks:
            for item in peaks.group(1).split(","):
                phase, mib = item.split()
                row["peak_mib_" + phase] = float(mib)
        hertz = report.get("hertz") or {}
        for key in ("error_half_width", "error_contact_radius", "error_max_pressure", "error_l2"):
            if key in hertz:
                row["hertz_" + key] = hertz[key]
        rows.append(row)
        print("%-28s %s" % (name, " ".join("%s=%.3g" % (k, v) for k, v in row.items() if isinstance(v, float))),
              flush=True)
    new = not os.path.exists(arguments.out)
    with open(arguments.out, "a", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=COLUMNS, restval="")
        if new:
            writer.writeheader()
        writer.writerows(rows)


if __name__ == "__main__":
    main()
