#!/usr/bin/python3
"""Draws incompressible.png from incompressible.csv (bench_incompressible's output) and prints
the README's table: Hertz errors in b, p0 and L2 for each discretisation and Poisson's ratio.

    /usr/bin/python3 benchmarks/incompressible/plot.py [out/incompressible]
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

directory = sys.argv[1] if len(sys.argv) > 1 else "out/incompressible"
rows = list(csv.DictReader(open(os.path.join(directory, "incompressible.csv"))))
variants = list(dict.fromkeys(r["variant"] for r in rows))
labels = {
    "order1": "3-node (hertz.json)",
    "order2": "6-node (hertz-order2.json)",
    "mixed": "6-node mixed (same mesh)",
    "order2_fine": "6-node, contact size 0.004",
    "mixed_fine": "6-node mixed, contact size 0.004",
}

figure, axes = plt.subplots(1, 3, figsize=(13, 4))
for variant in variants:
    points = [r for r in rows if r["variant"] == variant and r["status"] == "converged"]
    x = [0.5 - float(r["nu"]) for r in points]
    style = "o-" if "mixed" in variant else ("s--" if variant.startswith("order2") else "^:")
    for ax, key in zip(axes, ["error_half_width", "error_max_pressure", "error_l2"]):
        ax.loglog(x, [max(1e-3, 100 * abs(float(r[key]))) for r in points], style, label=labels.get(variant, variant))
for ax, title in zip(axes, ["|b error| against Hertz", "|p0 error| against Hertz", "L2 pressure error"]):
    ax.set_title(title)
    ax.set_xlabel("0.5 − ν")
    ax.set_ylabel("%")
    ax.invert_xaxis()
    ax.axhline(5, color="gray", ls=":", lw=1)
    ax.grid(True, which="both", alpha=0.3)
axes[0].legend(fontsize=8)
figure.tight_layout()
png = os.path.join(directory, "incompressible.png")
figure.savefig(png, dpi=80)
print("wrote", png)

print("\n| discretisation | DOFs | ν | b error | p0 error | L2 error | P |")
print("|---|---|---|---|---|---|---|")
for variant in variants:
    for r in (r for r in rows if r["variant"] == variant):
        if r["status"] != "converged":
            print(f"| {labels.get(variant, variant)} | {r['dofs']} | {r['nu']} | {r['status']} | | | |")
            continue
        print(f"| {labels.get(variant, variant)} | {r['dofs']} | {r['nu']} | {100 * float(r['error_half_width']):+.2f}% | "
              f"{100 * float(r['error_max_pressure']):+.2f}% | {100 * float(r['error_l2']):.2f}% | {float(r['force']):.6g} |")
