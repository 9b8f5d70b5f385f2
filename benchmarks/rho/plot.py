#!/usr/bin/python3
"""Figures and the summary table of the ρ benchmark, from its CSVs alone (bench_rho writes them).

    /usr/bin/python3 benchmarks/rho/plot.py [RESULTS_DIR]

RESULTS_DIR (default: benchmarks/rho/results beside this file) holds sweep.csv, auto.csv and
meshes.csv; the figures iterations_vs_rho.png and iterations_vs_h.png are written there and the
summary table (Markdown, for the README) is printed.
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def predicted_plain(fraction, rho_max, lam_min, lam_max, tol):
    """Fixed-step projected gradient on a block with spectrum [lam_min, lam_max]: the error
    contracts by max |1 − ρμ| per step, so iterations ≈ ln(1/tol) / −ln(that)."""
    rho = fraction * rho_max
    q = max(abs(1 - rho * lam_min), abs(1 - rho * lam_max))
    return math.log(1 / tol) / -math.log(q) if q < 1 else math.inf


def predicted_accelerated(fraction, rho_max, lam_min, lam_max, tol):
    """Nesterov's constant-momentum rate 1 − √(ρ λ_min), valid for ρ ≤ 1/λ_max."""
    rho = fraction * rho_max
    if rho * lam_max > 1:
        return math.inf
    return math.log(1 / tol) / -math.log(1 - math.sqrt(rho * lam_min))


def slope(xs, ys):
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    results = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "results")
    sweep = read(os.path.join(results, "sweep.csv"))
    auto = read(os.path.join(results, "auto.csv"))
    meshes = read(os.path.join(results, "meshes.csv"))
    with open(os.path.join(results, "context.json")) as f:
        context = json.load(f)
    tol = float(context["tol"])
    sizes = sorted({float(m["mesh_size"]) for m in meshes}, reverse=True)
    mesh_of = {float(m["mesh_size"]): m for m in meshes}

    # (a) iterations against ρ/ρ_max, one panel per mesh.
    columns = 2 if len(sizes) > 1 else 1
    rows = (len(sizes) + columns - 1) // columns
    fig, axes = plt.subplots(rows, columns, figsize=(6.2 * columns, 4.4 * rows), squeeze=False)
    styles = {"uzawa": ("tab:blue", "o", "uzawa"), "uzawa_accel": ("tab:red", "s", "uzawa_accel")}
    for ax, h in zip(axes.flat, sizes):
        m = mesh_of[h]
        rho_max = float(m["rho_max"])
        fractions = [0.01 * (250 ** (i / 400)) for i in range(401)]
        for variant, (color, marker, label) in styles.items():
            rows_v = [r for r in sweep if float(r["mesh_size"]) == h and r["variant"] == variant]
            for status, fill, suffix in (("converged", color, ""), ("max_iterations", "none", " (capped)"),
                                         ("diverged", "none", " (diverged)")):
                pts = [(float(r["rho_over_rho_max"]), int(r["iterations"])) for r in rows_v if r["status"] == status]
                if pts and status == "diverged":
                    ax.scatter(*zip(*pts), marker="x", s=28, color=color, label=label + suffix, zorder=3)
                elif pts:
                    ax.scatter(*zip(*pts), marker=marker, s=28, facecolors=fill, edgecolors=color,
                               label=label + suffix, zorder=3)
            for r in auto:
                if float(r["mesh_size"]) == h and r["variant"] == variant:
                    ax.scatter([float(r["rho_over_rho_max"])], [int(r["iterations"])], marker="*", s=160,
                               color=color, edgecolors="black", zorder=4, label=label + " --rho auto")
        top = 3 * max(int(r["iterations"]) for r in sweep if float(r["mesh_size"]) == h)
        lam = (float(m["lambda_min_active"]), float(m["lambda_max_active"]))
        # Beyond the plot's top the prediction is drawn as a gap (it is infinite past 2/λ_max).
        plain = [n if n < top else math.nan for n in (predicted_plain(x, rho_max, *lam, tol) for x in fractions)]
        ax.plot(fractions, plain, "-", color="tab:blue", alpha=0.5, label="predicted, κ(S) of the active block")
        acc = [predicted_accelerated(x, rho_max, *lam, tol) for x in fractions]
        ax.plot(fractions, acc, ":", color="tab:red", alpha=0.7, label="predicted, Nesterov 1−√(ρλ_min)")
        ax.axvline(1.0, color="gray", lw=0.8, ls="--")
        ax.axvline(2 / lam[1] / rho_max, color="tab:blue", lw=0.8, ls=":")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(0.008, 3)
        ax.set_ylim(top=top)
        ax.set_title(f"h = {h:g} R: {m['dofs']} DOFs, {m['active_rows']} of {m['constraints']} rows active, "
                     f"κ = {lam[1] / lam[0]:.0f}", fontsize=9)
        ax.set_xlabel("ρ / ρ_max   (ρ_max = 2/λ_max(S) on the violated rows; dotted: 2/λ_max of the active block)",
                      fontsize=7)
        ax.set_ylabel(f"iterations to tol {tol:g}")
        ax.grid(True, which="both", alpha=0.25)
    for ax in list(axes.flat)[len(sizes):]:
        ax.axis("off")
    handles, labels = axes.flat[0].get_legend_handles_labels()
    unique = dict(zip(labels, handles))
    fig.legend(unique.values(), unique.keys(), loc="lower center", ncol=4, fontsize=8, frameon=False)
    fig.suptitle("Uzawa's iterations against the step ρ (Hertz scenes, plain and accelerated)", fontsize=11)
    fig.tight_layout(rect=(0, 0.08, 1, 0.97))
    fig.savefig(os.path.join(results, "iterations_vs_rho.png"), dpi=80)

    # (b) iterations against 1/h at the automatic step (ρ_opt for plain Uzawa), and the best of the sweep.
    def auto_iterations(variant):
        return {float(r["mesh_size"]): int(r["iterations"]) for r in auto if r["variant"] == variant}

    plain_auto, accel_auto = auto_iterations("uzawa"), auto_iterations("uzawa_accel")
    best = {}
    for h in sizes:
        conv = [int(r["iterations"]) for r in sweep
                if float(r["mesh_size"]) == h and r["variant"] == "uzawa" and r["status"] == "converged"]
        best[h] = min(conv) if conv else None
    inv_h = [1 / h for h in sizes]
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    series = [("uzawa at ρ_opt (--rho auto)", plain_auto, "tab:blue", "o-"),
              ("uzawa, best ρ of the sweep", best, "tab:cyan", "v--"),
              ("uzawa_accel (--rho auto)", accel_auto, "tab:red", "s-")]
    slopes = {}
    for label, data, color, style in series:
        ys = [data[h] for h in sizes]
        slopes[label] = slope(inv_h, ys)
        ax.plot(inv_h, ys, style, color=color, label=f"{label}: ∝ (1/h)^{slopes[label]:.2f}")
    kappa = [float(mesh_of[h]["lambda_max_active"]) / float(mesh_of[h]["lambda_min_active"]) for h in sizes]
    ax.plot(inv_h, [math.log(1 / tol) * k / 2 for k in kappa], ":", color="gray",
            label="ln(1/tol)·κ/2 (κ of the active block)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("1/h  (h = element size at the contact, in units of R)")
    ax.set_ylabel(f"iterations to tol {tol:g}")
    ax.set_title("Iterations against mesh refinement (Hertz scenes)", fontsize=11)
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(results, "iterations_vs_h.png"), dpi=80)

    # The summary table for the README.
    print("| h/R | DOFs | active / candidate rows | κ(S) active block | uzawa, auto ρ | best of sweep (at ρ/ρ_max) "
          "| auto / best | uzawa_accel, auto ρ | accel / plain | first divergent ρ/ρ_max (plain) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for h in sizes:
        m = mesh_of[h]
        rows_p = sorted((float(r["rho_over_rho_max"]), r) for r in sweep
                        if float(r["mesh_size"]) == h and r["variant"] == "uzawa")
        best_row = min((r for _, r in rows_p if r["status"] == "converged"), key=lambda r: int(r["iterations"]))
        first_div = next((x for x, r in rows_p if r["status"] == "diverged"), math.nan)
        last_conv = max(x for x, r in rows_p if r["status"] == "converged")
        k = float(m["lambda_max_active"]) / float(m["lambda_min_active"])
        print(f"| {h:g} | {m['dofs']} | {m['active_rows']} / {m['constraints']} | {k:.0f} | {plain_auto[h]} "
              f"| {best_row['iterations']} ({float(best_row['rho_over_rho_max']):.3g}) "
              f"| {plain_auto[h] / int(best_row['iterations']):.2f} | {accel_auto[h]} "
              f"| {accel_auto[h] / plain_auto[h]:.3f} | {first_div:.3g} (last converged {last_conv:.3g}) |")
    for label, s in slopes.items():
        print(f"slope of {label}: {s:.2f}")


if __name__ == "__main__":
    main()
