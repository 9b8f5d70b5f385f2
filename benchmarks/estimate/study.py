#!/usr/bin/python3
"""The energy-error estimate measured (docs/estimate.md): effectivity and cost.

    /usr/bin/python3 benchmarks/estimate/study.py --contactqp build/contactqp --out benchmarks/estimate/results

Effectivity: Hertz's half cylinder (scenes/hertz.json's problem on a coarser mesh) on nested meshes,
level n = the same coarse Gmsh mesh split n times (sizes and grading 2^n smaller with
`refinements` n), P1 and P2, against the finest level's strain energy: the true energy error is
sqrt(2 (E_h - E_ref)) (docs/estimate.md, "The true error from energies"). Cost: the estimate's
time against the solve's on shipped scenes. Writes OUT/effectivity.csv, OUT/cost.csv,
OUT/context.json and prints both tables as Markdown.
"""
import argparse
import csv
import json
import math
import os
import platform
import subprocess
import tempfile
import time

HERTZ = {
    "model": "plane_strain",
    "material": {"E": 1.0, "nu": 0.3},
    "body": {"shape": "half_disc", "radius": 1.0, "symmetry": True, "mesh": {}},
    "load": {"type": "displacement", "boundary": "top", "value": [None, -0.016]},
    "obstacle": {"type": "plane", "point": [0.0, 0.0], "normal": [0.0, 1.0]},
    "solver": {"backend": "active_set", "tol": 1e-11},
}


def run(contactqp, scene_path, extra=()):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "result.json")
        proc = subprocess.run([contactqp, "solve", scene_path, "--json", out, "--quiet", *extra],
                              capture_output=True, text=True)
        if proc.returncode not in (0, 1):
            raise SystemExit(f"{scene_path}: exit {proc.returncode}: {proc.stderr.strip()}")
        with open(out) as f:
            return json.load(f)


def hertz_level(tmp, level, order):
    scale = 2.0 ** -level
    scene = json.loads(json.dumps(HERTZ))
    scene["body"]["mesh"] = {"size": 0.25 * scale, "contact_size": 0.025 * scale, "grading": 0.2 * scale,
                             "refinements": level, "order": order}
    path = os.path.join(tmp, f"hertz-{order}-{level}.json")
    with open(path, "w") as f:
        json.dump(scene, f)
    return path


SPHERE = {
    "model": "solid",
    "material": {"E": 1.0, "nu": 0.3},
    "body": {"shape": "hemisphere", "radius": 1.0, "symmetry": True, "mesh": {}},
    "load": {"type": "displacement", "boundary": "top", "value": [None, None, -0.01]},
    "obstacle": {"type": "plane", "point": [0.0, 0.0, 0.0], "normal": [0.0, 0.0, 1.0]},
    "solver": {"backend": "active_set", "tol": 1e-10},
}


def sphere_level(tmp, level, order):
    scale = 2.0 ** -level
    scene = json.loads(json.dumps(SPHERE))
    scene["body"]["mesh"] = {"size": 0.4 * scale, "contact_size": 0.04 * scale, "grading": 0.6 * scale,
                             "refinements": level, "order": order}
    path = os.path.join(tmp, f"sphere-{order}-{level}.json")
    with open(path, "w") as f:
        json.dump(scene, f)
    return path


def effectivity(contactqp, finest, name="hertz-2d", make=hertz_level, orders=(1, 2)):
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for order in orders:
            hertz_level = make
            reference = run(contactqp, hertz_level(tmp, finest, order))
            energy = reference["strain_energy"]
            previous = None
            for level in range(finest):
                r = run(contactqp, hertz_level(tmp, level, order))
                e = r["error_estimate"]
                difference = r["strain_energy"] - energy
                error = math.sqrt(2 * difference) if difference > 0 else float("nan")
                rate = math.log2(previous / e["energy_norm"]) if previous else float("nan")
                previous = e["energy_norm"]
                rows.append({"scene": name, "order": order, "level": level, "dofs": r["dofs"],
                             "strain_energy": r["strain_energy"], "reference_energy": energy,
                             "reference_dofs": reference["dofs"], "true_error": error,
                             "estimate": e["energy_norm"], "recovery": e["recovery"], "contact": e["contact"],
                             "effectivity": e["energy_norm"] / error, "estimate_rate": rate,
                             "relative": e["relative"]})
    return rows


def cost(contactqp, root, repeats):
    scenes = ["scenes/hertz.json", "scenes/hertz-order2.json", "scenes/hertz-sphere.json", "scenes/two-cylinders.json",
              "scenes/mindlin-cylinders.json", "scenes/punch.json"]
    rows = []
    for scene in scenes:
        best = None
        for _ in range(repeats):
            r = run(contactqp, os.path.join(root, scene))
            if best is None or r["timings"]["total"] < best["timings"]["total"]:
                best = r
        t = best["timings"]
        # The solve's time: factorisation and iterations (every backend phase between assembly and certify).
        solve = sum(v for k, v in t.items() if k in ("factorize", "solve", "spectrum"))
        e = best["error_estimate"]
        rows.append({"scene": scene, "dofs": best["dofs"], "status": best["status"], "solve_seconds": solve,
                     "estimate_seconds": t["estimate"], "ratio": t["estimate"] / solve if solve > 0 else float("nan"),
                     "total_seconds": t["total"], "estimate": e["energy_norm"], "relative": e["relative"]})
    return rows


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


def markdown(rows, columns):
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    for r in rows:
        cells = []
        for c in columns:
            v = r[c]
            cells.append(f"{v:.3g}" if isinstance(v, float) else str(v))
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--contactqp", default="build/contactqp")
    parser.add_argument("--out", default="benchmarks/estimate/results")
    parser.add_argument("--finest", type=int, default=4, help="the reference level (refinements, at most 4)")
    parser.add_argument("--finest-3d", type=int, default=2, help="the sphere's reference level (0: no 3D rows)")
    parser.add_argument("--repeats", type=int, default=3, help="runs per cost scene; the fastest is kept")
    args = parser.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    os.makedirs(args.out, exist_ok=True)
    eff = effectivity(args.contactqp, args.finest)
    if args.finest_3d > 0:
        eff += effectivity(args.contactqp, args.finest_3d, "hertz-3d", sphere_level, (1,))
    write_csv(os.path.join(args.out, "effectivity.csv"), eff)
    print(markdown(eff, ["scene", "order", "level", "dofs", "true_error", "estimate", "recovery", "contact", "effectivity",
                         "estimate_rate"]))
    costs = cost(args.contactqp, root, args.repeats)
    write_csv(os.path.join(args.out, "cost.csv"), costs)
    print()
    print(markdown(costs, ["scene", "dofs", "solve_seconds", "estimate_seconds", "ratio", "total_seconds",
                           "relative"]))
    revision = subprocess.run(["git", "-C", root, "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
    json.dump({"git_revision": revision, "date": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
               "cores": os.cpu_count(), "machine": platform.machine(), "python": platform.python_version()},
              open(os.path.join(args.out, "context.json"), "w"), indent=2)


if __name__ == "__main__":
    main()
