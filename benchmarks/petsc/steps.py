#!/usr/bin/python3
"""A load path at scale on the distributed run (docs/petsc-measurements.md, "Load steps"): a scene pushed in
STEPS equal steps (its first displacement load named and scaled 1/STEPS, 2/STEPS, ..., 1) solved
by the petsc backend under mpirun -n RANKS, beside one linear solve of the same A by the same KSP
and hierarchy (--no-contact: the contact solve's reference, measured in the same session). Each
rank runs under /usr/bin/time -v (its peak resident memory).

Prints and writes OUT/steps-table.md: per step the hierarchy's set-up (the first step's only),
the contact solve, the certificate, active-set steps, Krylov iterations, preconditioner set-ups
and the contact solve's time over the linear solve's; memory per rank and per DOF. Also OUT/steps.json, OUT/linear.json (the runs' result files), OUT/context.json.

usage: benchmarks/petsc/steps.py BUILD_DIR SCENE OUT_DIR [RANKS [STEPS]]   (default 2 ranks, 5 steps)
Run it under flock /work/coord/heavy.lock when the scene needs more than 3 GB."""
import datetime
import json
import os
import re
import subprocess
import sys

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")


def path_scene(scene, out, steps):
    """The scene with its first displacement load named `push` and scaled along the path."""
    with open(scene) as f:
        text = json.load(f)
    loads = text["load"] if isinstance(text["load"], list) else [text["load"]]
    push = next(load for load in loads if load["type"] == "displacement" and any(v for v in load["value"] if v))
    push["name"] = "push"
    text["load"] = loads
    # Any other named load keeps its full value along the path.
    others = {load["name"]: 1.0 for load in loads if load.get("name") and load is not push}
    text["steps"] = [{"factors": dict(others, push=(k + 1) / steps)} for k in range(steps)]
    path = os.path.join(out, "path-scene.json")
    with open(path, "w") as f:
        json.dump(text, f, indent=1)
    return path


def run(cli, ranks, scene, out, name, extra):
    """One run, each rank under /usr/bin/time -v; its result JSON and the ranks' peaks (MiB)."""
    timed = ["/bin/sh", "-c", 'exec /usr/bin/time -v -o "$0-${OMPI_COMM_WORLD_RANK:-0}.txt" "$@"',
             os.path.join(out, "time-" + name), cli, "solve", scene, "--backend", "petsc", "--quiet",
             "--json", os.path.join(out, name + ".json")] + extra
    command = (["mpirun", "-n", str(ranks), "--oversubscribe"] if ranks > 1 else []) + timed
    done = subprocess.run(command, env=ENV, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit("benchmarks/petsc/steps.py: %s ended with exit %d: %s" % (name, done.returncode, done.stderr[-500:]))
    with open(os.path.join(out, name + ".json")) as f:
        result = json.load(f)
    peaks = []
    for rank in range(ranks):
        with open(os.path.join(out, "time-%s-%d.txt" % (name, rank))) as f:
            peaks.append(int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", f.read()).group(1)) / 1024)
    return result, peaks


def main(build, scene, out, ranks="2", steps="5"):
    ranks, steps = int(ranks), int(steps)
    os.makedirs(out, exist_ok=True)
    cli = os.path.join(build, "contactqp")
    linear, linear_peaks = run(cli, ranks, scene, out, "linear", ["--no-contact"])
    path, path_peaks = run(cli, ranks, path_scene(scene, out, steps), out, "steps", [])
    one_solve = linear["timings"]["iterate"]
    dofs = path["dofs"]
    lines = ["%s, %d DOFs, %d ranks, %d steps (%s)" % (os.path.basename(scene), dofs, ranks, steps,
                                                          datetime.date.today().isoformat()),
             "",
             "one linear solve of A (--no-contact): %.2f s, %d Krylov iterations; hierarchy set-up %.2f s" %
             (one_solve, linear["solver"]["krylov_iterations"], linear["timings"]["factorize"]),
             "contact path: set-up %.2f s (once), steps below; whole run %.1f s" %
             (path["timings"]["factorize"], path["timings"]["total"]),
             "",
             "| step | push | P | set-up s | contact solve s | certificate s | active-set steps | Krylov iterations "
             "| set-ups | contact solve / one linear solve |",
             "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for k, step in enumerate(path["steps"]):
        d = step["diagnostics"]
        lines.append("| %d | %g | %.6g | %.2f | %.2f | %.2f | %d | %d | %d | %.2f |" % (
            k + 1, step["factors"]["push"], step["total_force"], d.get("factorize_seconds", 0), d["iterate_seconds"],
            d.get("certify_seconds", 0), d["outer_iterations"], d["krylov_iterations"],
            d.get("preconditioner_setups", 0), d["iterate_seconds"] / one_solve))
    lines += ["",
              "peak resident memory per rank (MiB): path %s, linear solve %s; summed over the ranks %.0f bytes per DOF" %
              (", ".join("%.0f" % p for p in path_peaks), ", ".join("%.0f" % p for p in linear_peaks),
               sum(path_peaks) * 1048576 / dofs)]
    text = "\n".join(lines) + "\n"
    print(text, end="")
    with open(os.path.join(out, "steps-table.md"), "w") as f:
        f.write(text)
    with open(os.path.join(out, "context.json"), "w") as f:
        json.dump({"date": datetime.datetime.now().isoformat(timespec="seconds"), "scene": scene, "ranks": ranks,
                   "steps": steps, "cpus": os.cpu_count(), "command": " ".join(sys.argv)}, f, indent=1)
    return 0


if __name__ == "__main__":
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    sys.exit(main(*sys.argv[1:]))
