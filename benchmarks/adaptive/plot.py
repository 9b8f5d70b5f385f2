#!/usr/bin/python3
"""Draws docs/adaptive.md's figures ("The trade measured").

convergence.png, from results/points.csv (study.py) alone: per family, the energy estimate
eta / sqrt(2E) and the error of the quantity users read first (p0; the force on the punch, whose
pressure is singular at the rim) against the DOFs, for the adaptive run, the hand-graded meshes
and uniform refinement, with the optimal rate N^(-p/d) for comparison. The error is against the
family's reference (the run with the smallest estimated error of all, whose own point is left
out).

adapted_mesh.png: an adaptive run of Hertz's half cylinder from one element size
(scenes/hertz.json, contact_size = size, to 4 % with --vtu: coarse enough to see its elements),
its last mesh coloured by each element's indicator eta_T (the ParaView field error_indicator),
whole and near the contact.

    /usr/bin/python3 benchmarks/adaptive/plot.py [--cli build/contactqp] [--skip-mesh]
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy  # noqa: E402
import vtk  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from matplotlib.colors import LogNorm  # noqa: E402
from vtk.util.numpy_support import vtk_to_numpy  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
RESULTS = os.path.join(HERE, "results")
METHODS = [("adaptive", "tab:red", "o"), ("hand-graded", "tab:blue", "s"), ("uniform", "tab:gray", "^")]


def family_order(family):
    """(element order, dimension) from a family's name, e.g. "hertz 3D P2" -> (2, 3)."""
    words = family.split()
    return int([w for w in words if w.startswith("P")][-1][1:]), int([w for w in words if w.endswith("D")][-1][:-1])


def draw_convergence(points_csv, out):
    rows = list(csv.DictReader(open(points_csv)))
    families = list(dict.fromkeys(r["family"] for r in rows))
    fig, axes = plt.subplots(2, len(families), figsize=(3.3 * len(families), 6.4), squeeze=False)
    for column, family in enumerate(families):
        mine = [r for r in rows if r["family"] == family]
        order, dim = family_order(family)
        quantity = "max_pressure" if mine[0].get("max_pressure") else "total_force"
        top, bottom = axes[0][column], axes[1][column]
        for method, colour, marker in METHODS:
            runs = sorted((r for r in mine if r["method"] == method), key=lambda r: int(r["dofs"]))
            if not runs:
                continue
            n = [int(r["dofs"]) for r in runs]
            top.loglog(n, [float(r["eta_relative"]) for r in runs], marker=marker, color=colour, label=method)
            # The reference's own point (error 0) has no place on a log scale.
            errors = [(int(r["dofs"]), abs(float(r[quantity + "_error"]))) for r in runs]
            errors = [(d, e) for d, e in errors if e > 0]
            if errors:
                bottom.loglog(*zip(*errors), marker=marker, color=colour, label=method)
        # The optimal rate, through the adaptive run's last point.
        adaptive = sorted((r for r in mine if r["method"] == "adaptive"), key=lambda r: int(r["dofs"]))
        if adaptive:
            n1, e1 = int(adaptive[-1]["dofs"]), float(adaptive[-1]["eta_relative"])
            n0 = n1 / 100
            top.loglog([n0, n1], [e1 * 100 ** (order / dim), e1], "k--", linewidth=0.8,
                       label="N^(-%d/%d)" % (order, dim))
        top.set_title(family, fontsize=10)
        top.set_ylabel("eta / sqrt(2E)")
        bottom.set_ylabel("|%s error| (relative)" % ("p0" if quantity == "max_pressure" else "force"))
        bottom.set_xlabel("DOFs")
        for ax in (top, bottom):
            ax.grid(True, which="both", linewidth=0.3)
        top.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    print("plot: wrote %s" % out, file=sys.stderr)


def extrapolation_check(points_csv):
    """Prints how far an estimate of a quantity's error from an adaptive run's last two cycles,
    |Q_k - Q_(k-1)| / |Q_k| * eta_k / (eta_(k-1) - eta_k) (the error taken to fall like eta),
    lies from the true error against the reference: the ratio's range per family and quantity
    over the cycles between the first and the reference (docs/estimate.md, "The contact force")."""
    rows = list(csv.DictReader(open(points_csv)))
    print("extrapolated error / true error, adaptive cycles 2 to the last but one:")
    for family in dict.fromkeys(r["family"] for r in rows):
        cycles = sorted((r for r in rows if r["family"] == family and r["method"] == "adaptive"),
                        key=lambda r: int(r["dofs"]))
        for quantity in ("max_pressure", "zone", "total_force", "tangential_force", "stick_zone"):
            ratios = []
            for last, this in zip(cycles[:-2], cycles[1:-1]):
                if not this.get(quantity):
                    break
                q0, q1 = float(last[quantity]), float(this[quantity])
                e0, e1 = float(last["eta_relative"]), float(this["eta_relative"])
                true = abs(float(this[quantity + "_error"]))
                if e0 > e1 and true > 0 and q1 != 0:
                    ratios.append(abs(q1 - q0) / abs(q1) * e1 / (e0 - e1) / true)
            if ratios:
                print("  %-24s %-16s %.2g to %.3g over %d cycles" % (family, quantity, min(ratios), max(ratios),
                                                                     len(ratios)))


def read_cells(path):
    """Vertices, each cell's corner vertices (the first three of a 6-node triangle) and its
    error_indicator, from contactqp's ParaView file of a 2D run."""
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    points = vtk_to_numpy(grid.GetPoints().GetData())[:, :2]
    cells = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(grid.GetNumberOfCells(), -1)[:, :3]
    indicator = vtk_to_numpy(grid.GetCellData().GetArray("error_indicator"))
    return points, cells, indicator


def draw_adapted_mesh(cli, out):
    scene = json.load(open(os.path.join(ROOT, "scenes", "hertz.json")))
    scene["body"]["mesh"]["contact_size"] = scene["body"]["mesh"]["size"]
    scene["body"]["mesh"].pop("grading", None)
    scene["solver"] = {"backend": "active_set", "tol": 1e-10}
    scene["adapt"] = {"target": 0.04}
    directory = tempfile.mkdtemp(prefix="adaptive-plot-")
    path, vtu, result = (os.path.join(directory, name) for name in ("scene.json", "out.vtu", "out.json"))
    json.dump(scene, open(path, "w"))
    subprocess.run([cli, "solve", path, "--quiet", "--vtu", vtu, "--json", result], check=True,
                   stdout=subprocess.DEVNULL)
    cycles = json.load(open(result))["adaptive"]["cycles"]
    # The first cycle alone: the coarse mesh and the indicators that drove the first refinement.
    first_vtu, first_path = os.path.join(directory, "first.vtu"), os.path.join(directory, "first.json")
    json.dump({key: value for key, value in scene.items() if key != "adapt"}, open(first_path, "w"))
    subprocess.run([cli, "solve", first_path, "--quiet", "--vtu", first_vtu], check=True, stdout=subprocess.DEVNULL)
    first = read_cells(first_vtu)
    points, cells, indicator = read_cells(vtu)
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    both = numpy.concatenate([indicator, first[2]])
    norm = LogNorm(vmin=max(both.max() * 1e-4, both[both > 0].min()), vmax=both.max())
    ax = axes[0]
    ax.add_collection(PolyCollection(first[0][first[1]], array=numpy.maximum(first[2], norm.vmin), cmap="viridis",
                                     norm=norm, edgecolors="k", linewidths=0.2))
    ax.set_aspect("equal")
    ax.set_xlim(first[0][:, 0].min(), first[0][:, 0].max())
    ax.set_ylim(first[0][:, 1].min(), first[0][:, 1].max())
    ax.set_title("cycle 1: %d DOFs, the error at the contact" % cycles[0]["dofs"], fontsize=10)
    axes = axes[1:]
    # The contact point: the lowest vertex (the half disc rests on the plane y = 0); a symmetric
    # scene models the side x >= 0 only.
    bottom = points[numpy.argmin(points[:, 1])]
    b = json.load(open(result))["contact"]["half_width"]
    left = bottom[0] if points[:, 0].min() >= bottom[0] - 1e-12 else bottom[0] - 3 * b
    for ax, zoom in zip(axes, (False, True)):
        polygons = PolyCollection(points[cells], array=numpy.maximum(indicator, norm.vmin), cmap="viridis", norm=norm,
                                  edgecolors="k", linewidths=0.2)
        ax.add_collection(polygons)
        ax.set_aspect("equal")
        if zoom:
            ax.set_xlim(left, bottom[0] + 3 * b)
            ax.set_ylim(bottom[1], bottom[1] + 1.5 * b)
            ax.axvline(bottom[0] + b, color="w", linewidth=1, linestyle="--")
            ax.set_title("near the contact (dashed: b = %.4g)" % b, fontsize=10)
        else:
            ax.set_xlim(points[:, 0].min(), points[:, 0].max())
            ax.set_ylim(points[:, 1].min(), points[:, 1].max())
            ax.set_title("cycle %d: the whole body" % len(cycles), fontsize=10)
    fig.colorbar(polygons, ax=list(axes), label="element indicator eta_T")
    fig.suptitle("Hertz's half cylinder from one size (%s), adapted to 4 %%: %d cycles, %d elements, %d DOFs; "
                 "the indicators come out about equal, as the plan aims" % (
                     scene["body"]["mesh"]["size"], len(cycles), cycles[-1]["elements"], cycles[-1]["dofs"]),
                 fontsize=10)
    fig.savefig(out, dpi=90)
    print("plot: wrote %s (cycles: %s DOFs)" % (out, ", ".join(str(c["dofs"]) for c in cycles)), file=sys.stderr)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--cli", default=os.path.join(ROOT, "build", "contactqp"))
    parser.add_argument("--skip-mesh", action="store_true", help="draw only convergence.png (no run)")
    args = parser.parse_args()
    points_csv = os.path.join(RESULTS, "points.csv")
    if not os.path.exists(points_csv):
        sys.exit("plot: %s not found: run benchmarks/adaptive/study.py first" % points_csv)
    draw_convergence(points_csv, os.path.join(RESULTS, "convergence.png"))
    extrapolation_check(points_csv)
    if not args.skip_mesh:
        draw_adapted_mesh(args.cli, os.path.join(RESULTS, "adapted_mesh.png"))


if __name__ == "__main__":
    main()
