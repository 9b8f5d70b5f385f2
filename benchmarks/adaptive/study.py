#!/usr/bin/python3
"""Adaptive meshes against hand-graded and uniform ones (docs/adaptive.md, "The trade measured").

For each scene family: the adaptive run from one element size (the scene's far-field `size`
everywhere, no grading), every cycle a mesh; uniform meshes of that size halved level by
level; the shipped hand-graded scene and its size function halved level by level. Every run
is `contactqp solve --json`, timed by its own JSON ("total": mesh to estimate). The reference
is the run with the smallest estimated error of all. Prints, per family, quantity and
tolerance, the fewest DOFs and the least whole-run time (for adaptive: the cycles up to that one) at which the quantity is
within the tolerance of the reference and stays within it on every finer mesh of that method,
the estimate's rate in N and, on linear elements without friction, its effectivity on every
adaptive cycle. Writes every point to results/points.csv (a family run again replaces its own
rows; the others stay); benchmarks/adaptive/plot.py draws them.

    /usr/bin/python3 benchmarks/adaptive/study.py [--cli build/contactqp] [--families "hertz 2D P1,..."]
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

# name, scene, element order, quantities read, adaptive target, DOF cap, uniform levels, hand-graded levels
ALL = ["max_pressure", "zone", "total_force"]
FRICTION = ["tangential_force", "stick_zone"]  # Q and the stick zone's c (b and a in 2D and 3D)
FAMILIES = [
    ("hertz 2D P1", "scenes/hertz.json", 1, ALL, 0.0025, 600000, 7, 4),
    ("two cylinders 2D P1", "scenes/two-cylinders.json", 1, ALL, 0.004, 400000, 6, 3),
    ("hertz 3D P1", "scenes/hertz-sphere.json", 1, ALL, 0.08, 100000, 3, 2),
    ("hertz 3D P2", "scenes/hertz-sphere.json", 2, ALL, 0.005, 250000, 3, 2),
    ("punch 3D P2", "scenes/punch.json", 2, ["total_force"], 0.015, 250000, 3, 2),
    # Coulomb friction along the load path (pressed, then sheared to Q = 0.7 muP): b/R = 0.002,
    # so uniform meshes of the far-field size do not reach the zone within the cap.
    ("mindlin on plane 2D P1", "scenes/mindlin-on-plane.json", 1, ALL + FRICTION, 0.004, 400000, 6, 3),
]
TOLERANCES = [0.01, 0.003, 0.001]


def run(cli, scene, directory, name):
    path = os.path.join(directory, name + ".json")
    out = os.path.join(directory, name + ".out.json")
    with open(path, "w") as f:
        json.dump(scene, f)
    done = subprocess.run([cli, "solve", path, "--quiet", "--json", out], capture_output=True, text=True)
    if done.returncode not in (0, 1) or not os.path.exists(out):
        sys.exit("study: %s failed: %s" % (name, done.stderr.strip()))
    return json.load(open(out))


def quantities(result, dim):
    # Against the obstacles, or the first pair's where bodies touch only each other (as the
    # adaptive cycles report them).
    contact = result["pairs"][0] if result.get("pairs") and not result["contact"]["total_force"] else result["contact"]
    zone = contact.get("half_width") if dim == 2 else contact.get("contact_radius")
    force = contact["total_force"] if "force_on_node_body" not in contact else math.hypot(*contact["force_on_node_body"])
    out = {"max_pressure": contact["max_pressure"], "zone": zone, "total_force": force}
    if "tangential_force" in contact:
        out["tangential_force"] = contact["tangential_force"]
        out["stick_zone"] = contact["stick_half_width" if dim == 2 else "stick_radius"]
    return out


def meshes(scene):
    """The mesh sections of a scene's generated bodies."""
    bodies = scene["bodies"] if "bodies" in scene else [scene["body"]]
    return [body["mesh"] for body in bodies if body.get("shape") != "mesh"]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--cli", default=os.path.join(ROOT, "build", "contactqp"))
    parser.add_argument("--families", default="", help="comma-separated names, e.g. \"hertz 2D P1,punch 3D P2\"; "
                        "default: all")
    parser.add_argument("--out", default=os.path.join(HERE, "results"))
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = []
    directory = tempfile.mkdtemp(prefix="adaptive-study-")
    chosen = [name.strip() for name in args.families.split(",") if name.strip()]
    unknown = [name for name in chosen if name not in [f[0] for f in FAMILIES]]
    if unknown:
        sys.exit("study: --families: unknown %s; valid: %s" % (", ".join(unknown), ", ".join(f[0] for f in FAMILIES)))
    for family, scene_path, order, names, target, cap, uniform_levels, graded_levels in FAMILIES:
        if chosen and family not in chosen:
            continue
        base = json.load(open(os.path.join(ROOT, scene_path)))
        dim = 3 if base["model"] == "solid" else 2
        base["solver"] = {"backend": "active_set", "tol": 1e-10}
        for mesh in meshes(base):
            mesh["order"] = order
            mesh.pop("refinements", None)
        points = []  # (method, dofs, seconds, {quantity: value}, eta_relative, strain_energy)
        coarse = json.loads(json.dumps(base))
        for mesh in meshes(coarse):
            mesh["contact_size"] = mesh["size"]
            mesh.pop("grading", None)
        adaptive = json.loads(json.dumps(coarse))
        adaptive["adapt"] = {"target": target, "max_dofs": cap, "max_cycles": 30}
        print("study: %s adaptive" % family, file=sys.stderr)
        result = run(args.cli, adaptive, directory, "adaptive")
        elapsed = 0
        for cycle in result["adaptive"]["cycles"]:
            elapsed += cycle["seconds"]
            q = {key: cycle[key] for key in ALL + FRICTION if key in cycle}
            points.append(("adaptive", cycle["dofs"], elapsed, q, cycle["relative"], cycle["strain_energy"]))
        # Uniform: one size everywhere, halved level by level. Hand-graded: the scene's size
        # function min(size, contact_size + grading · d) halved everywhere.
        def scaled(scene, level, keys):
            scene = json.loads(json.dumps(scene))
            for mesh in meshes(scene):
                for key in keys:
                    mesh[key] = mesh.get(key, 0.1) / 2 ** level
            return scene

        def uniform(level):
            return scaled(coarse, level, ("size", "contact_size"))

        def graded(level):
            return scaled(base, level, ("size", "contact_size", "grading"))

        for method, make, levels in (("uniform", uniform, uniform_levels), ("hand-graded", graded, graded_levels)):
            for level in range(levels):
                print("study: %s %s %d" % (family, method, level), file=sys.stderr)
                r = run(args.cli, make(level), directory, "%s%d" % (method, level))
                points.append((method, r["dofs"], r["timings"]["total"], quantities(r, dim),
                               r["error_estimate"]["relative"], r["strain_energy"]))
                if r["dofs"] > cap:
                    break
        finest = min(points, key=lambda p: p[4])  # the smallest estimated error of all
        reference = finest[3]
        for method, dofs, seconds, q, relative, energy in points:
            rows.append({"family": family, "method": method, "dofs": dofs, "seconds": "%.4g" % seconds,
                         "eta_relative": "%.4g" % relative,
                         **{k: "%.9g" % q[k] for k in names},
                         **{k + "_error": "%.3g" % ((q[k] - reference[k]) / reference[k]) for k in names}})
        print("\n## %s (reference: %s at %d DOFs, eta/sqrt(2E) %.3g%%: %s)\n" % (
            family, finest[0], finest[1], 100 * finest[4], ", ".join("%s %.7g" % (k, reference[k]) for k in names)))
        print("| quantity | within | adaptive DOFs | adaptive time [s] | hand-graded DOFs | hand-graded time [s] | uniform DOFs | uniform time [s] |")
        print("|---|---|---:|---:|---:|---:|---:|---:|")
        for name in names:
            for tol in TOLERANCES:
                cells = []
                for method in ("adaptive", "hand-graded", "uniform"):
                    mine = sorted((p for p in points if p[0] == method and p is not finest), key=lambda p: p[1])
                    hit = None
                    for k, p in enumerate(mine):  # within tol here and on every finer mesh of the method
                        if all(abs(x[3][name] - reference[name]) <= tol * abs(reference[name]) for x in mine[k:]):
                            hit = p
                            break
                    cells += ["%d" % hit[1], "%.3g" % hit[2]] if hit else ["-", "-"]
                print("| %s | %g%% | %s |" % (name, 100 * tol, " | ".join(cells)))
        print("\nrate of eta/sqrt(2E) in N: the least-squares slope of log eta against log N over each")
        print("method's meshes within a factor 30 in N of its finest (the coarse pre-asymptotic ones left out):")
        for method in ("adaptive", "hand-graded", "uniform"):
            mine = sorted((p for p in points if p[0] == method), key=lambda p: p[1])
            mine = [p for p in mine if p[1] * 30 >= mine[-1][1]] if mine else []
            if len(mine) >= 2:
                x = [math.log(p[1]) for p in mine]
                y = [math.log(p[4]) for p in mine]
                mx, my = sum(x) / len(x), sum(y) / len(y)
                slope = sum((a - mx) * (b - my) for a, b in zip(x, y)) / sum((a - mx) ** 2 for a in x)
                print("  %-12s %.2f over %d meshes, %d to %d DOFs (optimal -p/d = %.2f)" % (
                    method, slope, len(mine), mine[0][1], mine[-1][1], -order / dim))
        # Effectivity from energies (docs/estimate.md, "The true error"): on a scene pushed by
        # prescribed displacements alone, E_h - E = 1/2 |u - u_h|^2 where faces do not
        # penetrate between nodes (linear elements); E is extrapolated from the last two adaptive
        # cycles with E_h - E proportional to N^(-2p/d), the optimal rate.
        cycles = [p for p in points if p[0] == "adaptive"]
        # Not with friction: the dissipation breaks the identity.
        if order == 1 and len(cycles) >= 4 and "tangential_force" not in names:
            (n1, e1), (n2, e2) = [(p[1], p[5]) for p in cycles[-2:]]
            k = 2.0 * order / dim
            exact = e2 - (e1 - e2) / (n2 ** k / n1 ** k - 1)
            print("\neffectivity eta / |u - u_h| on every adaptive cycle but the last two (E extrapolated: %.10g):" % exact)
            print("| cycle | DOFs | eta/sqrt(2E) | effectivity |")
            print("|---:|---:|---:|---:|")
            for i, p in enumerate(cycles[:-2]):
                # Below E: faces penetrate between nodes (a zone of one or two nodes), and the
                # energy no longer measures the error.
                effectivity = ("%.2f" % (p[4] * math.sqrt(2 * p[5]) / math.sqrt(2 * (p[5] - exact)))
                               if p[5] > exact else "- (E_h < E)")
                print("| %d | %d | %.3g%% | %s |" % (i + 1, p[1], 100 * p[4], effectivity))
        sys.stdout.flush()
    # The families not run this time keep their rows from an earlier run.
    path = os.path.join(args.out, "points.csv")
    if os.path.exists(path):
        ran = {row["family"] for row in rows}
        rows = [row for row in csv.DictReader(open(path)) if row["family"] not in ran] + rows
    with open(path, "w", newline="") as f:
        keys = sorted({k for r in rows for k in r}, key=lambda k: (k not in ("family", "method", "dofs"), k))
        writer = csv.DictWriter(f, fieldnames=keys)
        writer.writeheader()
        writer.writerows(rows)


if __name__ == "__main__":
    main()
