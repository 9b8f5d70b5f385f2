#!/usr/bin/python3
"""Draws docs/img/friction-*.png from the CSVs tools/friction_study.py writes into out/friction/
(nothing is solved here), and prints the tables of docs/friction.md.

    /usr/bin/python3 tools/plot_friction.py [out/friction]
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "out", "friction")
IMG = os.path.join(ROOT, "docs", "img")
MU = 0.3  # the shipped Mindlin scenes' coefficient


def rows(name):
    path = os.path.join(DATA, name)
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return [{k: (float(v) if v not in ("", None) and k not in ("scene", "status") else v) for k, v in r.items()}
                for r in csv.DictReader(f)]


def mindlin_q(x, b, c, p0):
    """Mindlin's traction along Q at |x| (per μ), b the zone's size, c the stick zone's."""
    x = numpy.abs(x)
    q = numpy.where(x < b, p0 * numpy.sqrt(numpy.clip(1 - (x / b) ** 2, 0, None)), 0.0)
    return q - numpy.where(x < c, p0 * (c / b) * numpy.sqrt(numpy.clip(1 - (x / c) ** 2, 0, None)), 0.0)


def summary(scene):
    return {int(r["step"]): r for r in rows("mindlin.csv") if r["scene"] == scene}


def profile_axes(ax, scene, ratio, step, radial):
    points = [r for r in rows(f"profile_{scene}_{ratio}.csv") if r["pressure"] > 0 or r["state"] > 0]
    s = summary(scene).get(step)
    if not points or not s:
        return
    b, c = s["size"], s["c"]
    p0 = max(r["pressure"] for r in points) if not points[0].get("hertz_pressure") else max(
        r["hertz_pressure"] for r in points)
    x = numpy.array([r["s"] for r in points])
    if not radial:
        x = x - 0.5 * (x.max() + x.min())
    q = numpy.array([r["tangential_traction"] for r in points]) / (MU * p0)
    state = numpy.array([r["state"] for r in points])
    grid = numpy.linspace(-1.05 * b if not radial else 0, 1.05 * b, 600)
    ax.plot(grid / b, mindlin_q(grid, b, c, 1.0), "k-", lw=1.2, label="Mindlin q / (μ p0)")
    ax.plot(grid / b, numpy.where(numpy.abs(grid) < b, numpy.sqrt(numpy.clip(1 - (grid / b) ** 2, 0, None)), 0), "k:",
            lw=1, label="μ p / (μ p0) (slip limit)")
    ax.scatter(x[state == 1] / b, q[state == 1], s=9, c="tab:blue", label="computed, stick", zorder=3)
    ax.scatter(x[state == 2] / b, q[state == 2], s=9, c="tab:red", label="computed, slip", zorder=3)
    for sign in ((1,) if radial else (-1, 1)):
        ax.axvline(sign * c / b, color="grey", lw=0.6, ls="--")
    ax.set_title(f"Q/(μP) = {s['load_ratio']:.2f}: c/{'a' if radial else 'b'} = {s['c_computed'] / b:.3f} "
                 f"(Mindlin {c / b:.3f}), L2 {100 * s['error_l2']:.1f}%", fontsize=9)
    ax.set_xlabel("r / a" if radial else "x / b")


def figure_cylinders():
    figure, axes = plt.subplots(1, 2, figsize=(11, 3.8), sharey=True)
    for ax, (ratio, step) in zip(axes, (("0.3", 2), ("0.7", 3))):
        profile_axes(ax, "mindlin-cylinders", ratio, step, radial=False)
    axes[0].set_ylabel("tangential traction q / (μ p0)")
    axes[0].legend(fontsize=8, loc="lower center")
    figure.suptitle("Two identical cylinders (scenes/mindlin-cylinders.json): q(x) against Cattaneo–Mindlin", fontsize=10)
    figure.tight_layout()
    figure.savefig(os.path.join(IMG, "friction-cylinders.png"), dpi=110)


def spheres_row(axes, ratio, step, figure):
    """One shear step of the spheres: pressure, traction along Q and the states seen from below
    (the half model y >= 0 mirrored to the whole patch), then q(r) against Mindlin's."""
    points = [r for r in rows(f"profile_mindlin-spheres_{ratio}.csv") if r["pressure"] > 0 or r["state"] > 0]
    s = summary("mindlin-spheres").get(step)
    if not points or not s:
        return
    a, c = s["size"], s["c"]
    x = numpy.array([r["x"] for r in points]) / a
    y = numpy.array([r["y"] for r in points]) / a
    p = numpy.array([r["pressure"] for r in points])
    q = numpy.array([r["tangential_traction"] for r in points])
    state = numpy.array([r["state"] for r in points])
    both = numpy.concatenate  # the mirror image y -> -y of the modelled half
    X, Y = both([x, x]), both([y, -y])
    circle = numpy.linspace(0, 2 * math.pi, 200)

    def circles(ax):
        ax.plot(numpy.cos(circle), numpy.sin(circle), "k-", lw=0.8)
        ax.plot(c / a * numpy.cos(circle), c / a * numpy.sin(circle), "c--", lw=1.2)
        ax.set_aspect("equal")
        ax.set_xlabel("x / a  (Q along +x)")

    for ax, values, title, cmap in ((axes[0], p, "pressure p", "viridis"), (axes[1], q, "traction along Q", "magma")):
        drawn = ax.scatter(X, Y, c=both([values, values]), s=4, cmap=cmap)
        figure.colorbar(drawn, ax=ax, shrink=0.75)
        circles(ax)
        ax.set_title(f"Q/(μP) = {s['load_ratio']:.2f}: {title}", fontsize=9)
    states = both([state, state])
    # The vertices of 6-node faces carry next to no force (their consistent weight is 0), so
    # their μλ_N is next to 0 and most of them slip: drawn apart, they do not count in c.
    force = numpy.array([r["force"] for r in points])
    bare = both([force, force]) < 1e-2 * numpy.median(force[force > 0])
    axes[2].scatter(X[(states == 1) & ~bare], Y[(states == 1) & ~bare], s=4, c="tab:blue", label="stick")
    axes[2].scatter(X[(states == 2) & ~bare], Y[(states == 2) & ~bare], s=4, c="tab:red", label="slip")
    axes[2].scatter(X[bare], Y[bare], s=3, c="lightgrey", label="face vertex (no force)")
    circles(axes[2])
    axes[2].set_title(f"stick and slip: c/a = {s['c_computed'] / a:.3f} (Mindlin {c / a:.3f}, cyan)", fontsize=9)
    axes[2].legend(fontsize=7, loc="upper right")
    axes[0].set_ylabel("y / a  (seen from below)")
    r = numpy.hypot(x, y) * a
    p0 = max(rr["hertz_pressure"] for rr in points)
    axes[3].scatter(r[state == 1] / a, q[state == 1] / (MU * p0), s=5, c="tab:blue", label="computed, stick")
    axes[3].scatter(r[state == 2] / a, q[state == 2] / (MU * p0), s=5, c="tab:red", label="computed, slip")
    grid = numpy.linspace(0, 1.05 * a, 400)
    axes[3].plot(grid / a, mindlin_q(grid, a, c, 1.0), "k-", label="Mindlin")
    axes[3].plot(grid / a, numpy.sqrt(numpy.clip(1 - (grid / a) ** 2, 0, None)), "k:", label="μ p (slip limit)")
    axes[3].axvline(c / a, color="grey", ls="--", lw=0.6)
    axes[3].set_xlabel("r / a")
    axes[3].set_ylabel("q / (μ p0)")
    axes[3].legend(fontsize=7)
    axes[3].set_title(f"q(r): L2 error {100 * s['error_l2']:.1f}%", fontsize=9)


def figure_spheres():
    figure, axes = plt.subplots(2, 4, figsize=(18, 8.4))
    for row, (ratio, step) in zip(axes, (("0.3", 2), ("0.7", 3))):
        spheres_row(row, ratio, step, figure)
    figure.suptitle("Two identical spheres (scenes/mindlin-spheres.json): the contact patch from below, "
                    "Hertz's a (black) and Mindlin's c (cyan)", fontsize=10)
    figure.tight_layout()
    figure.savefig(os.path.join(IMG, "friction-spheres.png"), dpi=100)


def figure_paths():
    figure, axes = plt.subplots(1, 3, figsize=(15, 3.8))
    study = rows("finite_body.csv")
    for target, marker in ((0.3, "o"), (0.7, "s")):
        pts = sorted((r for r in study if abs(r["load_ratio"] - target) < 0.02), key=lambda r: r["b_over_R"])
        if pts:
            axes[0].loglog([r["b_over_R"] for r in pts], [r["error_l2"] for r in pts], marker + "-",
                           label=f"L2 of q, Q/(μP) = {target}")
            axes[0].loglog([r["b_over_R"] for r in pts], [abs(r["error_c"]) for r in pts], marker + ":",
                           label=f"|c error|, Q/(μP) = {target}")
    axes[0].set_xlabel("b / R")
    axes[0].set_title("two cylinders: the finite bodies' share, against b/R", fontsize=9)
    axes[0].legend(fontsize=7)
    block = rows("steps_sliding-block.csv")
    if block:
        shear = [r.get("factor_shear", 0) for r in block]
        axes[1].plot(shear, [r["Q"] / (MU * r["P"]) for r in block], "o-", label="Q / (μ P)")
        axes[1].plot(shear, [r["c"] for r in block], "s-", label="stick half-width")
        axes[1].set_xlabel("shear factor (of 0.02)")
        axes[1].set_title("scenes/sliding-block.json: the block slides when Q = μP", fontsize=9)
        axes[1].legend(fontsize=8)
    curve = rows("steps_p-delta.csv")
    if curve:
        axes[2].plot([0] + [0.016 * r["factor_push"] for r in curve], [0] + [r["P"] for r in curve], "o-")
        axes[2].set_xlabel("push δ")
        axes[2].set_ylabel("P")
        axes[2].set_title("scenes/p-delta.json: P against δ, ten steps", fontsize=9)
    figure.tight_layout()
    figure.savefig(os.path.join(IMG, "friction-paths.png"), dpi=110)


def tables():
    print("| scene | Q/(μP) | c/b or c/a | Mindlin | c error | q L2 | Hertz b (a), p0 | β | DOFs |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows("mindlin.csv"):
        print(f"| {r['scene']} | {r['load_ratio']:.3f} | {r['c_computed'] / r['size']:.4f} | {r['c'] / r['size']:.4f} | "
              f"{100 * r['error_c']:+.2f}% | {100 * r['error_l2']:.2f}% | {100 * r['hertz_error_size']:+.2f}%, "
              f"{100 * r['hertz_error_p0']:+.2f}% | {r['beta']:.3f} | {int(r['dofs'])} |")


if __name__ == "__main__":
    os.makedirs(IMG, exist_ok=True)
    figure_cylinders()
    figure_spheres()
    figure_paths()
    tables()
