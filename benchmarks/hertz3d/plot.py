#!/usr/bin/python3
"""Draws benchmarks/hertz3d/results/{sphere,punch}.csv: the sphere's errors against Hertz as
the mesh is refined, 4- against 10-node tetrahedra, with the observed order of the L2 pressure
error in h = DOFs^(-1/3); and the punch's force against Boussinesq as the block grows and the
mesh is refined. Writes sphere.png and tables.md beside the CSVs.

    /usr/bin/python3 benchmarks/hertz3d/plot.py [RESULTS_DIR]
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def fitted_order(points):
    """Least-squares slope of log(error) against log(h), h = DOFs^(-1/3)."""
    xs = [math.log(float(p["dofs"]) ** (-1.0 / 3)) for p in points]
    ys = [math.log(float(p["error_l2"])) for p in points]
    n = len(xs)
    if n < 2:
        return float("nan")
    mx, my = sum(xs) / n, sum(ys) / n
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def main(results):
    sphere = rows(os.path.join(results, "sphere.csv"))
    punch = rows(os.path.join(results, "punch.csv"))
    out = ["## Hertz's sphere: errors against Hertz by element order", "",
           "| element | contact_size [R] | DOFs | a error | p0 error | L2 error | time [s] |",
           "|---|---:|---:|---:|---:|---:|---:|"]
    figure, axis = plt.subplots(figsize=(6, 4))
    for order, name in (("1", "4-node tetrahedra"), ("2", "10-node tetrahedra")):
        family = [r for r in sphere if r["order"] == order]
        for r in family:
            out.append(f"| {name} | {float(r['contact_size']):g} | {int(r['dofs'])} | "
                       f"{100 * float(r['error_contact_radius']):+.2f}% | {100 * float(r['error_max_pressure']):+.2f}% | "
                       f"{100 * float(r['error_l2']):.2f}% | {float(r['seconds']):.2f} |")
        order_fit = fitted_order(family)
        out.append(f"| {name}: observed order of the L2 error in h = DOFs^(-1/3) | | | | | {order_fit:.2f} | |")
        axis.loglog([int(r["dofs"]) for r in family], [100 * float(r["error_l2"]) for r in family], "o-",
                    label=f"{name} (order {order_fit:.2f} in h)")
    axis.set_xlabel("DOFs")
    axis.set_ylabel("L2 pressure error against Hertz [%]")
    axis.set_title("Hertz's sphere (quarter model, a/R ≈ 0.1)")
    axis.grid(True, which="both", alpha=0.3)
    axis.legend()
    figure.tight_layout()
    figure.savefig(os.path.join(results, "sphere.png"), dpi=110)
    out += ["", "## Boussinesq's punch: force against 2 a E* δ as the block grows", "",
            "| block [a] | contact_size [a] | DOFs | force error | shape error (r ≤ 0.8a) | time [s] |",
            "|---:|---:|---:|---:|---:|---:|"]
    for r in punch:
        out.append(f"| {float(r['block']):g} | {float(r['contact_size']):g} | {int(r['dofs'])} | "
                   f"{100 * float(r['error_force']):+.2f}% | {100 * float(r['shape_error']):.2f}% | {float(r['seconds']):.2f} |")
    with open(os.path.join(results, "tables.md"), "w") as f:
        f.write("\n".join(out) + "\n")
    print("\n".join(out))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "results"))
