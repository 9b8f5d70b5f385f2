#!/usr/bin/python3
"""Draws element_order.png from element_order.csv (bench_element_order's output) and prints,
for each accuracy level, the fewest DOFs each family needs to reach it.

    /usr/bin/python3 benchmarks/element_order/plot.py [out/element_order]
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402

directory = sys.argv[1] if len(sys.argv) > 1 else "out/element_order"
rows = [r for r in csv.DictReader(open(os.path.join(directory, "element_order.csv"))) if r["status"] == "converged"]
families = sorted({r["family"] for r in rows})
labels = {
    "order1": "3-node, grading 0.1 (hertz.json)",
    "order1_fast": "3-node, grading 0.3",
    "order2": "6-node, grading 0.1",
    "order2_graded": "6-node, grading 0.3 (hertz-order2.json)",
}

figure, axes = plt.subplots(1, 2, figsize=(11, 4.2))
for family in families:
    points = sorted((int(r["dofs"]), r) for r in rows if r["family"] == family)
    dofs = [d for d, _ in points]
    style = "o-" if family.startswith("order1") else "s-"
    axes[0].loglog(dofs, [100 * float(r["error_l2"]) for _, r in points], style, label=labels.get(family, family))
    axes[1].loglog(dofs, [100 * abs(float(r["force_error"])) for _, r in points], style, label=labels.get(family, family))
axes[0].axhline(0.7, color="gray", ls=":", lw=1)
axes[0].text(axes[0].get_xlim()[0] * 1.1, 0.72, "finite-body floor ≈ 0.7%", color="gray", fontsize=8)
axes[0].set_title("L2 pressure error against Hertz")
axes[1].set_title("|P − 0.008657| / 0.008657 (independent reference)")
for ax in axes:
    ax.set_xlabel("DOFs")
    ax.set_ylabel("%")
    ax.grid(True, which="both", alpha=0.3)
axes[0].set_yticks([0.5, 0.7, 1, 1.5, 2, 3, 5])
axes[0].get_yaxis().set_major_formatter(matplotlib.ticker.ScalarFormatter())
axes[0].legend(fontsize=8)
figure.tight_layout()
png = os.path.join(directory, "element_order.png")
figure.savefig(png, dpi=80)
print("wrote", png)

print("\nfewest DOFs reaching an L2 pressure error (against Hertz) at or below:")
levels = [0.03, 0.02, 0.015, 0.012, 0.01]
print("level   " + "  ".join(f"{f:>14}" for f in families))
for level in levels:
    cells = []
    for family in families:
        reached = [int(r["dofs"]) for r in rows if r["family"] == family and float(r["error_l2"]) <= level]
        cells.append(f"{min(reached):>14}" if reached else f"{'—':>14}")
    print(f"{100 * level:4.1f}%  " + "  ".join(cells))
