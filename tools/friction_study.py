#!/usr/bin/python3
"""Runs the friction scenes and studies of docs/friction.md with contactqp and writes their CSVs
into out/friction/ (plot_friction.py draws the figures from them, without running anything):

  profile_<scene>_<ratio>.csv   a Mindlin scene stopped at Q/(μP) = 0.3 or 0.7: the profile CSV
                                (s or r, pressure, tangential traction, Mindlin's, state, x, y, z)
  mindlin.csv                   one row per scene and shear step: Q/(μP), c and ours, the errors,
                                Hertz's errors, β, DOFs, seconds
  finite_body.csv               two identical cylinders at shrinking b/R (Q/(μP) = 0.3, 0.7): the
                                antisymmetric traction the finite bodies add, against b/R
  steps_<scene>.csv             sliding-block and p-delta: each step's factors, P, Q, b, c

    /usr/bin/python3 tools/friction_study.py [--skip-3d] [--skip-study]
"""
import csv
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CLI = os.path.join(ROOT, "build", "contactqp")
OUT = os.path.join(ROOT, "out", "friction")
SCENES = os.path.join(ROOT, "scenes")


def solve(scene, tag):
    """Writes `scene` (a dict) beside the shipped scenes' directory layout and solves it."""
    path = os.path.join(OUT, tag + ".json")
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    run = subprocess.run([CLI, "solve", path, "--json", path + ".out", "--csv", os.path.join(OUT, "profile_" + tag + ".csv"),
                          "--quiet"], capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"{tag}: contactqp exited {run.returncode}: {run.stderr.strip()}")
    with open(path + ".out") as f:
        return json.load(f)


def shipped(name):
    with open(os.path.join(SCENES, name + ".json")) as f:
        return json.load(f)


def zone_of(step_or_result):
    """The Mindlin comparison of a step or a result: the first pair's, else the obstacles'."""
    if "pairs" in step_or_result and step_or_result["pairs"]:
        return step_or_result["pairs"][0]
    return step_or_result["contact"]["obstacles"][0] if "contact" in step_or_result else step_or_result


def mindlin_rows(name, result):
    rows = []
    for k, step in enumerate(result["steps"]):
        pair = step["pairs"][0] if step.get("pairs") else step
        m = pair.get("mindlin")
        if not m:
            continue
        two_d = "half_width" in m
        hertz = zone_of(result).get("hertz", {})
        rows.append({
            "scene": name, "step": k + 1, "dofs": result["dofs"], "seconds": result["timings"]["total"],
            "load_ratio": m["load_ratio"], "beta": m["dundurs_beta"],
            "size": m["half_width" if two_d else "contact_radius"],
            "c": m["stick_half_width" if two_d else "stick_radius"],
            "c_computed": m["stick_half_width_computed" if two_d else "stick_radius_computed"],
            "error_c": m["error_stick_half_width" if two_d else "error_stick_radius"],
            "error_l2": m["error_l2"], "slip_displacement": m["slip_displacement"],
            "hertz_error_size": hertz.get("error_half_width", hertz.get("error_contact_radius", "")),
            "hertz_error_p0": hertz.get("error_max_pressure", ""), "hertz_error_l2": hertz.get("error_l2", ""),
            "iterations": step["iterations"], "step_seconds": step["seconds"]})
    return rows


def mindlin_scenes(names):
    """Each Mindlin scene whole (its mindlin rows; its profile is the last step's, Q/(μP) about
    0.7), and stopped after the first shear step (the profile at about 0.3)."""
    rows = []
    for name in names:
        scene = shipped(name)
        result = solve(scene, f"{name}_0.7")
        rows += mindlin_rows(name, result)
        solve(dict(scene, steps=scene["steps"][:2]), f"{name}_0.3")
    return rows


def cylinders(push, shear, contact_size):
    scene = shipped("mindlin-cylinders")
    for body in scene["bodies"]:
        body["mesh"]["contact_size"] = contact_size
    loads = scene["bodies"][0]["load"]
    loads[0]["value"] = [None, -push]
    loads[1]["value"] = [shear, None]
    return scene


def finite_body_study():
    """Two identical cylinders at b/R from 0.05 to 0.002 (the push scaled, b/h about 40): the shear
    displacement that gives Q/(μP) = 0.3 and 0.7 found by a secant, and the errors there."""
    rows = []
    for push in (0.01, 0.0025, 5e-4, 1.3e-4, 2.5e-5):
        contact_size = 0.002 * (push / 0.01) ** 0.5 / 1.3
        for target in (0.3, 0.7):
            shear, points = push * 0.15 * target / 0.3, []
            for _ in range(6):
                scene = cylinders(push, shear, contact_size)
                scene["steps"] = scene["steps"][:1] + [{"factors": {"shear": 1}}]
                result = solve(scene, "finite_body")
                m = result["pairs"][0]["mindlin"]
                points.append((shear, m["load_ratio"]))
                if abs(m["load_ratio"] - target) < 0.01:
                    break
                if len(points) == 1:
                    shear *= target / m["load_ratio"]
                else:
                    (s1, r1), (s2, r2) = points[-2], points[-1]
                    shear = s2 + (target - r2) * (s2 - s1) / (r2 - r1)
            rows.append({"push": push, "contact_size": contact_size, "dofs": result["dofs"],
                         "b_over_R": m["half_width"], "load_ratio": m["load_ratio"],
                         "error_c": m["error_stick_half_width"], "error_l2": m["error_l2"]})
            print(f"finite body: b/R {m['half_width']:.4f} Q/(mu P) {m['load_ratio']:.3f} "
                  f"c {m['error_stick_half_width']:+.4f} L2 {m['error_l2']:.4f}", flush=True)
    return rows


def steps_rows(name):
    result = solve(shipped(name), name)
    rows = []
    for k, step in enumerate(result["steps"]):
        row = {"step": k + 1, "status": step["status"], "iterations": step["iterations"],
               "seconds": step["seconds"], "P": step["total_force"], "b": step.get("half_width", "")}
        row.update({"factor_" + n: f for n, f in step["factors"].items()})
        if "tangential_force" in step:
            row["Q"] = step["tangential_force"]
            row["c"] = step.get("stick_half_width", "")
        for r in step["reactions"][:1]:
            row["reaction_x"], row["reaction_y"] = r["force"][0], r["force"][1]
        rows.append(row)
    return rows


def write(name, rows):
    if not rows:
        return
    keys = list(dict.fromkeys(k for row in rows for k in row))
    with open(os.path.join(OUT, name), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=keys)
        writer.writeheader()
        writer.writerows(rows)


def main():
    os.makedirs(OUT, exist_ok=True)
    names = ["mindlin-cylinders", "mindlin-on-plane"] + ([] if "--skip-3d" in sys.argv else ["mindlin-spheres"])
    write("mindlin.csv", mindlin_scenes(names))
    for name in ("sliding-block", "p-delta"):
        write(f"steps_{name}.csv", steps_rows(name))
    if "--skip-study" not in sys.argv:
        write("finite_body.csv", finite_body_study())


if __name__ == "__main__":
    main()
