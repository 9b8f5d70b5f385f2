#!/usr/bin/python3
"""Loads by force along a load path: the approach of Hertz's sphere against Hertz's δ(P), and the
Cattaneo–Mindlin Q–slip curve up to gross slip. Runs the CLI on the shipped force scenes with load
steps, writes out/force/{delta,q_slip}.csv, draws docs/img/force-delta.png and
docs/img/force-q-slip.png, and prints the tables of docs/friction.md and docs/scenes-gallery.md.

    /usr/bin/python3 tools/force_study.py [path/to/contactqp]
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CLI = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "contactqp")
OUT = os.path.join(ROOT, "out", "force")
IMG = os.path.join(ROOT, "docs", "img")


def scene(name):
    with open(os.path.join(ROOT, "scenes", name)) as f:
        return json.load(f)


def solve(text, work, name):
    """Runs one scene; returns (exit status, result JSON or None, the summary's status line)."""
    path, result = os.path.join(work, name + ".json"), os.path.join(work, name + ".out.json")
    with open(path, "w") as f:
        json.dump(text, f)
    run = subprocess.run([CLI, "solve", path, "--json", result], capture_output=True, text=True)
    status = next((line.strip() for line in run.stdout.splitlines() if line.strip().startswith("status")), "")
    if not os.path.exists(result):
        return run.returncode, None, status
    with open(result) as f:
        return run.returncode, json.load(f), status


def write_csv(name, rows):
    os.makedirs(OUT, exist_ok=True)
    with open(os.path.join(OUT, name), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)


def approach_study(work):
    """hertz-sphere-force.json in ten steps of P: the top's move against Hertz's δ = a²/R."""
    s = scene("hertz-sphere-force.json")
    P = -s["load"]["value"][2]
    s["load"]["name"] = "press"
    factors = [0.1 * k for k in range(1, 11)]
    s["steps"] = [{"factors": {"press": f}} for f in factors]
    code, r, status = solve(s, work, "delta")
    assert code == 0 and r, status
    E, nu, R = s["material"]["E"], s["material"]["nu"], s["body"]["radius"]
    E_star = E / (1 - nu * nu)
    rows = []
    for step, f in zip(r["steps"], factors):
        (surface,) = [x for x in step["reactions"] if "displacement" in x]
        force = f * P
        a = (3 * force * R / (4 * E_star)) ** (1 / 3)
        rows.append({"P": force, "top_moved": -surface["displacement"][2], "hertz_delta": a * a / R,
                     "radius": step["contact_radius"] if "contact_radius" in step else step.get("half_width", ""),
                     "hertz_radius": a, "iterations": step["iterations"]})
    for row in rows:  # Hertz's δ less the top's move, per P/(E R): constant if it is the far field's share
        row["share"] = (row["hertz_delta"] - row["top_moved"]) * E * R / row["P"]
    write_csv("delta.csv", rows)
    return rows


def q_slip_study(work):
    """mindlin-force.json: P, then Q raised in steps to 0.99 μP; then μP(1 ± 1e-3) on their own."""
    s = scene("mindlin-force.json")
    mu = s["contact"]["friction"]["coefficient"]
    P = -s["bodies"][0]["load"][0]["value"][1]
    Q_full = s["bodies"][0]["load"][1]["value"][0]
    ratios = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.99]
    s["steps"] = [{"factors": {"push": 1}}] + [{"factors": {"push": 1, "shear": q * mu * P / Q_full}} for q in ratios]
    code, r, status = solve(s, work, "q_slip")
    assert code == 0 and r, status
    rows = []
    for step, q in zip(r["steps"][1:], ratios):
        (shear,) = [x for x in step["reactions"] if "displacement" in x and x["displacement"][0] is not None]
        m = step["pairs"][0]["mindlin"]
        rows.append({"Q_over_muP": m["load_ratio"], "asked": q, "cut_moved_x": shear["displacement"][0],
                     "stick_half_width": m["stick_half_width_computed"], "mindlin_stick": m["stick_half_width"],
                     "half_width": m["half_width"], "error_stick": m["error_stick_half_width"],
                     "slip_displacement": m["slip_displacement"], "iterations": step["iterations"]})
    # What slip adds: the cut's move less the finite bodies' compliance, which is linear in Q and
    # which a stuck run gives (μ = 1e3, Q = 0.5 μP of the scene's μ: no node slips).
    E_star = r["pairs"][0]["hertz"]["effective_modulus"]
    stuck = json.loads(json.dumps(s))
    stuck["contact"]["friction"]["coefficient"] = 1e3
    stuck["steps"] = [{"factors": {"push": 1}}, {"factors": {"push": 1, "shear": 0.5 * mu * P / Q_full}}]
    code, r_stuck, status = solve(stuck, work, "stuck")
    assert code == 0 and r_stuck, status
    (moved,) = [x for x in r_stuck["steps"][-1]["reactions"] if "displacement" in x and x["displacement"][0] is not None]
    compliance = moved["displacement"][0] / (0.5 * mu * P)
    for row in rows:
        Q = row["Q_over_muP"] * mu * P
        row["slip_part"] = row["cut_moved_x"] - Q * compliance
        q = row["Q_over_muP"]
        row["mindlin_slip"] = mu * P / (math.pi * E_star) * (q + (1 - q) * math.log(1 - q))
    write_csv("q_slip.csv", rows)
    edges = []
    for q in (1 - 1e-3, 1 + 1e-3):
        s["steps"] = [{"factors": {"push": 1}}, {"factors": {"push": 1, "shear": q * mu * P / Q_full}}]
        code, r, status = solve(s, work, "edge")
        edges.append((q, code, status))
    return rows, edges, (mu * P, E_star, compliance)


def draw_delta(rows):
    P = numpy.array([r["P"] for r in rows])
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 3.8))
    grid = numpy.linspace(0, P.max() * 1.05, 200)
    hertz = numpy.array(grid) ** (2 / 3) * (rows[-1]["hertz_delta"] / P[-1] ** (2 / 3))
    left.plot(grid, hertz, "k-", lw=1.2, label="Hertz δ = a²/R = (9P²/(16RE*²))^(1/3)")
    share = float(numpy.mean([r["share"] for r in rows]))
    left.plot(grid, hertz - share * grid, "k--", lw=1, label=f"Hertz δ − {share:.3f} P/(E R)")
    left.plot(P, [r["top_moved"] for r in rows], "o", color="tab:blue", label="the half ball's top (force load)")
    left.set_xlabel("P / (E R²)")
    left.set_ylabel("approach / R")
    left.legend(frameon=False)
    right.plot(P, [r["top_moved"] / r["hertz_delta"] for r in rows], "o-", color="tab:blue", label="top / Hertz δ")
    right.plot(P, [r["radius"] / r["hertz_radius"] for r in rows], "s-", color="tab:orange", label="a / Hertz a")
    right.axhline(1, color="k", lw=0.8)
    right.set_xlabel("P / (E R²)")
    right.set_ylabel("ratio to Hertz")
    right.legend(frameon=False)
    fig.tight_layout()
    fig.savefig(os.path.join(IMG, "force-delta.png"), dpi=110)


def draw_q_slip(rows, constants):
    muP, E_star, _ = constants
    q = numpy.array([r["Q_over_muP"] for r in rows])
    b = rows[0]["half_width"]
    scale = muP / (math.pi * E_star)  # Mindlin's slip at Q = μP
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 3.8))
    grid = numpy.linspace(0, 0.9999, 400)
    left.plot(grid + (1 - grid) * numpy.log(1 - grid), grid, "k-", lw=1.2,
              label="Mindlin (2D): (μP/πE*) [q + (1 − q) ln(1 − q)]")
    left.plot([r["slip_part"] / scale for r in rows], q, "o", color="tab:blue",
              label="the cut's move less the stuck compliance × Q")
    left.axhline(1, color="tab:red", lw=1, ls="--", label="gross slip (Q = μP: exit 1 above)")
    left.set_xlabel("what slip adds to the tangential move / (μP / πE*)")
    left.set_ylabel("Q / (μ P)")
    left.set_ylim(0, 1.08)
    left.legend(frameon=False, loc="lower right")
    grid = numpy.linspace(0, 1, 200)
    right.plot(grid, numpy.sqrt(1 - grid), "k-", lw=1.2, label="Mindlin c / b = sqrt(1 − Q/μP)")
    right.plot(q, [r["stick_half_width"] / b for r in rows], "o", color="tab:blue", label="stick half-width (nodes)")
    right.set_xlabel("Q / (μ P)")
    right.set_ylabel("c / b")
    right.legend(frameon=False)
    fig.tight_layout()
    fig.savefig(os.path.join(IMG, "force-q-slip.png"), dpi=110)


def main():
    with tempfile.TemporaryDirectory() as work:
        delta = approach_study(work)
        q_slip, edges, constants = q_slip_study(work)
    draw_delta(delta)
    draw_q_slip(q_slip, constants)
    print("| P | top moved | Hertz δ | ratio | (δ − top) E R / P | a / Hertz a | iterations |")
    print("|---:|---:|---:|---:|---:|---:|---:|")
    for r in delta:
        print(f"| {r['P']:.4g} | {r['top_moved']:.4g} | {r['hertz_delta']:.4g} | {r['top_moved'] / r['hertz_delta']:.4f} "
              f"| {r['share']:.4f} | {r['radius'] / r['hertz_radius']:.4f} | {r['iterations']:.0f} |")
    print()
    print(f"stuck compliance {constants[2]:.6g} per unit Q (mu = 1e3)")
    print("| Q/(μP) | cut moved along x | slip part | Mindlin's | c (nodes) | Mindlin's c | error (of b) | iterations |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in q_slip:
        print(f"| {r['Q_over_muP']:.3f} | {r['cut_moved_x']:.4g} | {r['slip_part']:.4g} | {r['mindlin_slip']:.4g} "
              f"| {r['stick_half_width']:.4g} | {r['mindlin_stick']:.4g} "
              f"| {100 * r['error_stick']:+.2f} % | {r['iterations']:.0f} |")
    for q, code, status in edges:
        print(f"Q = {q:.3f} μP: exit {code}: {status[:150]}")
    assert not any(math.isnan(r["top_moved"]) for r in delta)


if __name__ == "__main__":
    main()
