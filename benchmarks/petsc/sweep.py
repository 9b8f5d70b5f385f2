#!/usr/bin/python3
"""The petsc backend's distributed run on Hertz's sphere from 5e4 to 1.5e6 DOFs (docs/petsc-measurements.md,
"The sweep"): for each level (element order, contact_size, refinements) and each rank count,

  contact      [mpirun -n N] contactqp solve SCENE            (1 rank: --distributed)
  linear       [mpirun -n N] contactqp solve SCENE --no-contact: one linear solve of the same
               A by the same KSP and multigrid hierarchy, the contact solve's reference
  active_set   contactqp solve SCENE --backend active_set      (CHOLMOD, one process; levels
               up to --cholmod-dofs only: the factor of K stops fitting near 9e5 DOFs)
  before       the contact run with another build (--before BUILD: today's backend)

each under /usr/bin/time (peak resident set per rank). Prints one table (whole run, the
multigrid set-up, the solve's iterations, certify, CG iterations, set-ups, the contact solve over
the linear solve, peak MiB per rank), writes OUT/sweep.csv and draws OUT/sweep.png (whole run and
solve against DOFs). Runs one at a time: time them on a quiet machine.

usage: benchmarks/petsc/sweep.py BUILD [--before BUILD] [--levels 2:0.014:0 ...] [--ranks 1 2]
       [--out DIR] [--cholmod-dofs N]
A level is ORDER:CONTACT_SIZE:REFINEMENTS (the mesh of scenes/hertz-sphere.json changed so)."""
import argparse
import csv
import json
import os
import sys

from multigrid import run  # one contactqp run under /usr/bin/time: (JSON, wall, peak MiB)

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# From 5.6e4 to 1.34e6 DOFs with 10-node tetrahedra (the last is scenes/hertz-sphere-large.json),
# and 4-node ones from 7.1e4 to 1.5e6.
LEVELS = ["2:0.012:0", "2:0.0085:0", "2:0.005:1", "2:0.0035:1", "1:0.0047:0", "1:0.0025:1", "1:0.0016:1"]


def level_scene(level, out):
    """The sphere scene of one level, written to OUT/scenes; returns its path."""
    order, contact_size, refinements = level.split(":")
    with open(os.path.join(SOURCE, "scenes", "hertz-sphere.json")) as f:
        scene = json.load(f)
    mesh = scene["body"]["mesh"]
    mesh["order"] = int(order)
    mesh["contact_size"] = float(contact_size)
    if int(refinements) > 0:
        mesh["refinements"] = int(refinements)
    scene["solver"] = {"backend": "petsc", "tol": 1e-8}
    os.makedirs(os.path.join(out, "scenes"), exist_ok=True)
    path = os.path.join(out, "scenes", "sphere-p%s-cs%s-r%s.json" % (order, contact_size, refinements))
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    return path


def row(level, ranks, kind, outcome, linear=None):
    """One row of the table and the CSV from a run's JSON."""
    result, wall, peak = outcome
    out = {"level": level, "ranks": ranks, "run": kind, "wall": round(wall, 2), "peak_mib": round(peak)}
    if result is None:
        out["status"] = "failed"
        return out
    timings, solver = result.get("timings", {}), result.get("solver", {})
    solve = timings.get("factorize", 0.0) + timings.get("solve", 0.0)
    out.update({
        "status": result.get("status", "?"), "dofs": result.get("dofs", 0), "total": timings.get("total", 0.0),
        "mesh": timings.get("mesh", 0.0), "assemble": timings.get("assemble", 0.0),
        "setup": timings.get("factorize", 0.0), "iterate": timings.get("solve", 0.0), "solve": solve,
        "certify": timings.get("certify", 0.0), "outer": result.get("iterations", 0),
        "cg": int(solver.get("krylov_iterations", 0)), "setups": int(solver.get("preconditioner_setups", 0)),
        "a_error": (result.get("hertz") or {}).get("error_contact_radius"),
        "p0_error": (result.get("hertz") or {}).get("error_max_pressure"),
        "l2_error": (result.get("hertz") or {}).get("error_l2"),
    })
    if linear and linear[0] is not None:
        t = linear[0].get("timings", {})
        reference = t.get("factorize", 0.0) + t.get("solve", 0.0)
        out["contact_over_linear"] = round(solve / reference, 3) if reference > 0 else ""
    return out


def plot(rows, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    styles = {"contact": "o-", "linear": "s--", "active_set": "^:", "before": "x-."}
    for order in ("1", "2"):
        for ranks in sorted({r["ranks"] for r in rows}):
            for kind, style in styles.items():
                points = sorted((r["dofs"], r["total"], r["solve"]) for r in rows
                                if r["run"] == kind and r["ranks"] == ranks and r["level"].startswith(order + ":")
                                and r.get("status") == "converged")
                if not points:
                    continue
                label = "%s, %s-node, %d rank%s" % (kind, "10" if order == "2" else "4", ranks, "s" if ranks > 1 else "")
                axes[0].loglog([p[0] for p in points], [p[1] for p in points], style, label=label)
                axes[1].loglog([p[0] for p in points], [p[2] for p in points], style, label=label)
    axes[0].set_title("whole run")
    axes[1].set_title("solve: set-up + iterations (active_set: factor + iterations)", fontsize=10)
    for axis in axes:
        axis.set_xlabel("DOFs")
        axis.set_ylabel("seconds")
        axis.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("build")
    parser.add_argument("--before")
    parser.add_argument("--levels", nargs="+", default=LEVELS)
    parser.add_argument("--ranks", nargs="+", type=int, default=[1, 2])
    parser.add_argument("--out", default=os.path.join(SOURCE, "benchmarks", "petsc", "results", "sweep"))
    parser.add_argument("--cholmod-dofs", type=float, default=4e5)
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for level in args.levels:
        scene = level_scene(level, args.out)
        tag = level.replace(":", "_")
        dofs = None
        for ranks in args.ranks:
            extra = ["--distributed"] if ranks == 1 else []
            linear = run(args.build, scene, ranks, args.out, "%s-n%d-linear" % (tag, ranks), extra + ["--no-contact"])
            contact = run(args.build, scene, ranks, args.out, "%s-n%d-contact" % (tag, ranks), extra)
            rows.append(row(level, ranks, "linear", linear))
            rows.append(row(level, ranks, "contact", contact, linear))
            dofs = dofs or rows[-1].get("dofs")
            if args.before:
                before = run(args.before, scene, ranks, args.out, "%s-n%d-before" % (tag, ranks), extra)
                rows.append(row(level, ranks, "before", before))
        if dofs and dofs <= args.cholmod_dofs:
            outcome = run(args.build, scene, 1, args.out, "%s-active-set" % tag, [], backend="active_set")
            rows.append(row(level, 1, "active_set", outcome))
        print("done: %s" % level, file=sys.stderr, flush=True)

    columns = ["level", "dofs", "ranks", "run", "status", "wall", "total", "mesh", "assemble", "setup", "iterate",
               "solve", "certify", "outer", "cg", "setups", "contact_over_linear", "peak_mib", "a_error", "p0_error", "l2_error"]
    with open(os.path.join(args.out, "sweep.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        writer.writeheader()
        for r in rows:
            writer.writerow(r)
    plot(rows, os.path.join(args.out, "sweep.png"))
    print("| level | DOFs | ranks | run | status | total | set-up | iterate | certify | outer | CG | set-ups "
          "| contact/linear | peak MiB/rank |")
    print("|---|---:|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        if r.get("status") == "failed":
            print("| %s | | %d | %s | failed | | | | | | | | | %d |" % (r["level"], r["ranks"], r["run"], r["peak_mib"]))
            continue
        print("| %s | %d | %d | %s | %s | %.1f | %.1f | %.1f | %.1f | %s | %s | %s | %s | %d |" %
              (r["level"], r["dofs"], r["ranks"], r["run"], r["status"], r["total"], r["setup"], r["iterate"],
               r["certify"], r["outer"], r["cg"], r["setups"], r.get("contact_over_linear", ""), r["peak_mib"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
