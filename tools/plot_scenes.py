#!/usr/bin/python3
"""Solves each shipped scene with contactqp (--json, --csv, --vtu into out/scenes/) and draws
docs/img/<scene>.png: the deformed body coloured by von Mises stress with the obstacles, and
the contact pressure along each obstacle with Hertz's profile where it applies.

    /usr/bin/python3 tools/plot_scenes.py [scene.json ...]    (default: every scene but hertz-large)
"""
import csv
import glob
import json
import math
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy  # noqa: E402
import vtk  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402
from vtk.util.numpy_support import vtk_to_numpy  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CLI = os.path.join(ROOT, "build", "contactqp")
OUT = os.path.join(ROOT, "out", "scenes")
IMG = os.path.join(ROOT, "docs", "img")


def read_vtu(path):
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    points = vtk_to_numpy(grid.GetPoints().GetData())[:, :2]
    cells = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(grid.GetNumberOfCells(), -1)
    data = grid.GetPointData()
    fields = {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i)) for i in range(data.GetNumberOfArrays())}
    # A 6-node triangle (vertices, then mid-sides 01, 12, 20) drawn as four 3-node ones.
    if cells.shape[1] == 6:
        a, b, c, ab, bc, ca = cells.T
        cells = numpy.vstack([numpy.c_[a, ab, ca], numpy.c_[ab, b, bc], numpy.c_[ca, bc, c], numpy.c_[ab, bc, ca]])
    return points, cells, fields


def rotation(scene):
    angle = math.radians(scene.get("transform", {}).get("rotate_degrees", 0.0))
    return numpy.array([[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]])


def draw_obstacles(ax, scene, extent):
    R = rotation(scene)
    obstacles = scene["obstacle"] if isinstance(scene["obstacle"], list) else [scene["obstacle"]]
    for o in obstacles:
        if o["type"] == "plane":
            p, n = R @ numpy.array(o["point"]), R @ numpy.array(o["normal"], float)
            n /= numpy.linalg.norm(n)
            t = numpy.array([n[1], -n[0]])
            line = numpy.array([p - 3 * extent * t, p + 3 * extent * t])
            ax.fill(*numpy.r_[line, [line[1] - 3 * extent * n, line[0] - 3 * extent * n]].T, color="0.85", zorder=0)
            ax.plot(*line.T, color="0.3", lw=1)
        elif o["type"] == "circle":
            c = R @ numpy.array(o["center"])
            ax.add_patch(plt.Circle(c, o["radius"], color="0.85", ec="0.3", zorder=0))
        else:
            pts = numpy.array([R @ numpy.array(p) for p in o["points"]])
            ax.plot(*pts.T, color="0.3", lw=1)


def plot(scene_path):
    name = os.path.splitext(os.path.basename(scene_path))[0]
    os.makedirs(OUT, exist_ok=True)
    base = os.path.join(OUT, name)
    subprocess.run([CLI, "solve", scene_path, "--json", base + ".json", "--csv", base + ".csv", "--vtu", base + ".vtu"],
                   check=True, stdout=subprocess.DEVNULL)
    scene = json.load(open(scene_path))
    result = json.load(open(base + ".json"))
    points, cells, fields = read_vtu(base + ".vtu")
    u = fields["displacement"][:, :2]
    extent = numpy.ptp(points, axis=0).max()
    scale = 0.05 * extent / max(numpy.abs(u).max(), 1e-300)
    moved = points + scale * u

    figure, (left, right) = plt.subplots(1, 2, figsize=(11, 4.4))
    draw_obstacles(left, scene, extent)
    shade = left.tripcolor(Triangulation(moved[:, 0], moved[:, 1], cells), fields["von_mises"], shading="gouraud", cmap="viridis")
    figure.colorbar(shade, ax=left, shrink=0.8, label="von Mises stress")
    low, high = moved.min(axis=0), moved.max(axis=0)
    margin = 0.08 * extent
    left.set_xlim(low[0] - margin, high[0] + margin)
    left.set_ylim(low[1] - margin, high[1] + margin)
    left.set_aspect("equal")
    left.set_title(f"{name}: displacement × {scale:.3g}", fontsize=10)

    rows = list(csv.DictReader(open(base + ".csv")))
    for obstacle in sorted({int(r["obstacle"]) for r in rows}):
        mine = sorted((float(r["s"]), r) for r in rows if int(r["obstacle"]) == obstacle)
        s = [x for x, _ in mine]
        right.plot(s, [float(r["pressure"]) for _, r in mine], ".-", ms=3, lw=0.8, label=f"obstacle {obstacle}")
        if mine and mine[0][1]["hertz_pressure"] != "":
            right.plot(s, [float(r["hertz_pressure"]) for _, r in mine], "k--", lw=0.8, label="Hertz" if obstacle == 0 else None)
    hertz = result.get("hertz")
    note = f"P = {result['contact']['total_force']:.4g}"
    if hertz:
        note += f", Hertz errors: b {100 * hertz['error_half_width']:+.2f}%, p0 {100 * hertz['error_max_pressure']:+.2f}%"
    right.set_title(note, fontsize=10)
    right.set_xlabel("s along the obstacle")
    right.set_ylabel("contact pressure")
    right.grid(alpha=0.3)
    right.legend(fontsize=8)
    figure.tight_layout()
    os.makedirs(IMG, exist_ok=True)
    png = os.path.join(IMG, name + ".png")
    figure.savefig(png, dpi=80)
    plt.close(figure)
    print("wrote", png)


if __name__ == "__main__":
    scenes = sys.argv[1:] or sorted(p for p in glob.glob(os.path.join(ROOT, "scenes", "*.json")) if "-large" not in p)
    for path in scenes:
        plot(path)
