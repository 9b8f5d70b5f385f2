#!/usr/bin/python3
"""The memory figures of docs/petsc-measurements.md, "Distributed runs: memory per rank", from the measured
peaks: benchmarks/petsc/results/distributed/peaks.csv (one row per rank of each run: its peak
resident memory in KiB and how it was measured), or a memory.csv that benchmarks/petsc/memory.py
wrote (its peak_mib column).

Prints, per run, the sum over the ranks of the peaks per DOF and the largest rank against that
sum / N; then fits each rank's peak of the distributed runs as

    peak = fixed + per_dof · (DOFs the rank owns, taken as DOFs / ranks)

(least squares over every measured rank) and projects what a rank needs at 1e6 and 1e7 DOFs per
rank for 1e7 and 1e8 DOFs in all. Rank 0 holds in addition the coarse Gmsh mesh (8^n times
smaller than the fine one with body.mesh.refinements = n) and the gathered contact rows.

usage: benchmarks/petsc/projection.py [PEAKS_CSV]"""
import csv
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def read(path):
    rows = []
    with open(path) as f:
        for r in csv.DictReader(f):
            if r.get("peak_kib"):
                peak = float(r["peak_kib"]) * 1024
            elif r.get("peak_mib"):
                peak = float(r["peak_mib"]) * 1048576
            else:
                continue
            rows.append({"run": r.get("run", "distributed"), "scene": r.get("scene", ""), "dofs": float(r["dofs"]),
                         "ranks": int(r["ranks"]), "rank": int(r["rank"]), "peak": peak})
    return rows


def main(path=os.path.join(HERE, "results", "distributed", "peaks.csv")):
    rows = read(path)
    runs = {}
    for r in rows:
        runs.setdefault((r["run"], r["scene"], r["ranks"]), []).append(r)
    print("| run | scene | DOFs | ranks | peak per rank [GiB] | sum per DOF | largest / (sum / N) |")
    print("|---|---|---:|---:|---|---:|---:|")
    for (run, scene, n), group in runs.items():
        peaks = [r["peak"] for r in sorted(group, key=lambda r: r["rank"])]
        total = sum(peaks)
        print("| %s | %s | %.3g | %d | %s | %.2f KB | %.2f |" % (
            run, scene, group[0]["dofs"], n, " / ".join("%.2f" % (p / 2**30) for p in peaks),
            total / group[0]["dofs"] / 1000, max(peaks) / (total / n)))
    points = [(r["dofs"] / r["ranks"], r["peak"]) for r in rows if r["run"] == "distributed"]
    if len({round(x) for x, _ in points}) < 2:
        print("\n(the fit needs distributed runs of two sizes)")
        return 0
    m = len(points)
    sx, sy = sum(x for x, _ in points), sum(y for _, y in points)
    sxx, sxy = sum(x * x for x, _ in points), sum(x * y for x, y in points)
    per_dof = (m * sxy - sx * sy) / (m * sxx - sx * sx)
    fixed = (sy - per_dof * sx) / m
    print("\nfit over %d ranks of the distributed runs: peak per rank = %.0f MiB + %.2f KB per owned DOF" % (
        m, fixed / 2**20, per_dof / 1000))
    print("\n| DOFs | DOFs per rank | ranks | peak per rank | sum over ranks |")
    print("|---:|---:|---:|---:|---:|")
    for total_dofs in (1e7, 1e8):
        for per_rank in (1e6, 1e7):
            ranks = total_dofs / per_rank
            peak = fixed + per_dof * per_rank
            print("| %.0e | %.0e | %.0f | %.1f GiB | %.0f GiB |" % (total_dofs, per_rank, ranks, peak / 2**30,
                                                                   peak * ranks / 2**30))
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
