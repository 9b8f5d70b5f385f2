#!/usr/bin/python3
"""Figures and tables of benchmarks/scaling, drawn only from its CSV files.

    /usr/bin/python3 benchmarks/scaling/plot.py [RESULTS_DIR]

Reads scaling.csv (and orderings.csv when present) in RESULTS_DIR (default: results/ beside
this file) and writes scaling.png (time against DOFs per backend, log-log, with the line of
one linear solve of the same K; below it the ratio to that line) and scaling-table.md (the
README's summary, one line per mesh, then every run). Rows that did not run (time cap, skipped) are left out of the plot and kept
in the table.
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def number(text):
    try:
        value = float(text)
    except (TypeError, ValueError):
        return None
    return value if math.isfinite(value) else None


def read_rows(path):
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


def linear_line(rows):
    """Per level: DOFs and the fastest linear solve measured in any child on that mesh."""
    best = {}
    for row in rows:
        seconds = number(row["linear_total_seconds"])
        if seconds is None:
            continue
        dofs = int(row["dofs"])
        best[dofs] = min(seconds, best.get(dofs, math.inf))
    return sorted(best.items())


def plot(rows, path, time_cap):
    backends = []
    for row in rows:
        if row["backend"] not in backends:
            backends.append(row["backend"])
    figure, (top, bottom) = plt.subplots(2, 1, figsize=(7, 8), sharex=True,
                                         gridspec_kw={"height_ratios": [3, 2]})
    line = linear_line(rows)
    if line:
        top.plot([d for d, _ in line], [s for _, s in line], "k--", linewidth=1.5,
                 label="one linear solve of K (factorise + solve)")
    markers = "osD^v<>p*h"
    for index, backend in enumerate(backends):
        points = [(int(r["dofs"]), number(r["total_seconds"]), number(r["ratio_to_linear"]), r["status"])
                  for r in rows if r["backend"] == backend and number(r["total_seconds"]) is not None]
        if not points:
            continue
        marker = markers[index % len(markers)]
        (drawn,) = top.plot([p[0] for p in points], [p[1] for p in points], marker=marker, label=backend)
        colour = drawn.get_color()
        bottom.plot([p[0] for p in points], [p[2] for p in points], marker=marker, label=backend)
        for dofs, seconds, _, status in points:
            if status != "converged":
                top.annotate(status, (dofs, seconds), fontsize=7, textcoords="offset points", xytext=(4, 4))
        # A run killed at the time cap: a cross at the cap in the backend's colour, labelled.
        capped = [r for r in rows if r["backend"] == backend and r["status"] == "time_cap"]
        for row in capped:
            top.plot([int(row["dofs"])], [time_cap], "x", color=colour, markersize=9, mew=2)
            top.annotate(f"{backend}: killed at {time_cap:g} s", (int(row["dofs"]), time_cap), fontsize=7,
                         ha="right", textcoords="offset points", xytext=(-6, 4))
    top.set_xscale("log")
    top.set_yscale("log")
    top.set_ylabel("wall time of solve() [s]")
    top.set_title("Hertz contact: time against problem size (benchmarks/scaling)")
    top.grid(True, which="both", alpha=0.3)
    top.legend(fontsize=8)
    bottom.axhline(1.0, color="k", linestyle="--", linewidth=1)
    bottom.axhline(3.0, color="gray", linestyle=":", linewidth=1)
    bottom.set_yscale("log")
    bottom.set_xlabel("degrees of freedom")
    bottom.set_ylabel("time / one linear solve")
    bottom.grid(True, which="both", alpha=0.3)
    figure.tight_layout()
    figure.savefig(path, dpi=120)


def cell(value, digits=3):
    x = number(value)
    if x is None:
        return "—"
    if abs(x) >= 100:
        return f"{x:.0f}"
    return f"{x:.{digits}g}"


def table(rows):
    lines = ["| DOFs | candidates | backend | status | iterations | factorize [s] | condense [s] | iterate [s] | "
             "recover [s] | total [s] | linear solve [s] | ratio | peak memory [MiB] |",
             "|---:|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for row in rows:
        status = row["status"]
        if status in ("skipped", "time_cap", "crashed", "error"):
            status += f" ({row['reason']})"
        lines.append(f"| {int(row['dofs']):,} | {row['constraints']} | {row['backend']} | {status} | "
                     f"{row['iterations'] or '—'} | {cell(row['factorize_seconds'])} | {cell(row['condense_seconds'])} | "
                     f"{cell(row['iterate_seconds'])} | {cell(row['recover_seconds'])} | {cell(row['total_seconds'])} | "
                     f"{cell(row['linear_total_seconds'])} | {cell(row['ratio_to_linear'])} | "
                     f"{cell(row['peak_rss_mb'], 4)} |")
    return "\n".join(lines).replace(",", " ") + "\n"


def grouped(count):
    """12345 -> '12 345' (thin groups, as the README writes counts)."""
    return f"{int(count):,}".replace(",", " ")


def summary_table(rows):
    """One line per mesh: active_set against one linear solve, and every backend's total time."""
    backends = []
    for row in rows:
        if row["backend"] not in backends:
            backends.append(row["backend"])
    levels = []
    for row in rows:
        if row["dofs"] not in levels:
            levels.append(row["dofs"])
    lines = ["| DOFs | candidates | one linear solve [s] | active_set: iterations, time [s], ratio | " +
             " | ".join(f"{b} [s]" for b in backends if b != "active_set") + " | active_set peak memory [MiB] |",
             "|---:|---:|---:|---|" + "---:|" * (len(backends) - 1) + "---:|"]
    for dofs in levels:
        at = {row["backend"]: row for row in rows if row["dofs"] == dofs}
        active = at.get("active_set", {})
        cells = []
        for backend in backends:
            if backend == "active_set":
                continue
            row = at.get(backend)
            if row is None:
                cells.append("—")
            elif row["status"] == "converged":
                cells.append(f"{cell(row['total_seconds'])} ({row['iterations']} it.)")
            else:
                cells.append(row["status"])
        linear = cell(active.get("linear_total_seconds"))
        lines.append(f"| {grouped(dofs)} | {at[next(iter(at))]['constraints']} | {linear} | "
                     f"{active.get('iterations') or '—'}, {cell(active.get('total_seconds'))}, "
                     f"{cell(active.get('ratio_to_linear'))}× | " + " | ".join(cells) +
                     f" | {cell(active.get('peak_rss_mb'), 4)} |")
    return "\n".join(lines) + "\n"


def orderings_table(rows):
    lines = ["| DOFs | candidates | ordering | analyse [s] | factorise [s] | solve [s] | condense [s] | "
             "dense solve of all m columns [s] | nnz(L) | reached columns |",
             "|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|"]
    for row in rows:
        lines.append(f"| {int(row['dofs']):,} | {row['constraints']} | {row['ordering']} | {cell(row['analyse_seconds'])} | "
                     f"{cell(row['factorize_seconds'])} | {cell(row['solve_seconds'])} | {cell(row['condense_seconds'])} | "
                     f"{cell(row.get('dense_solve_seconds'))} | {float(row['factor_nonzeros']):.3g} | "
                     f"{row['reached_columns']} |")
    return "\n".join(lines).replace(",", " ") + "\n"


def main():
    directory = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "results")
    rows = read_rows(os.path.join(directory, "scaling.csv"))
    context_path = os.path.join(directory, "context.json")
    time_cap = 300.0
    if os.path.exists(context_path):
        with open(context_path) as handle:
            time_cap = float(json.load(handle).get("time_cap_seconds", time_cap))
    plot(rows, os.path.join(directory, "scaling.png"), time_cap)
    text = summary_table(rows) + "\n" + table(rows)
    orderings_path = os.path.join(directory, "orderings.csv")
    if os.path.exists(orderings_path):
        text += "\n" + orderings_table(read_rows(orderings_path))
    with open(os.path.join(directory, "scaling-table.md"), "w") as handle:
        handle.write(text)
    print(text, end="")
    print(f"wrote {os.path.join(directory, 'scaling.png')} and scaling-table.md")


if __name__ == "__main__":
    main()
