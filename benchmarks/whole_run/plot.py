#!/usr/bin/python3
"""The stacked per-phase figure and the table of benchmarks/whole_run, from its CSV only.

    /usr/bin/python3 benchmarks/whole_run/plot.py RESULTS.csv OUT.png OUT-table.md

One bar per run (grouped by label: 2D, 3D, before/after), its height the run's wall time from
process start to exit divided by one linear solve of the same K, stacked by phase; the line
at 1 is that linear solve. The table lists the seconds per phase.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# "contact_solve": factorize + solve (+ the petsc backend's transform), as whole_run.py adds them.
STACK = [("mesh", ["mesh", "model"]), ("assemble", ["assemble"]), ("solve", ["contact_solve"]),
         ("certify", ["certify"]), ("post-process", ["postprocess"]), ("write", ["write"])]


def main():
    rows = list(csv.DictReader(open(sys.argv[1], newline="")))
    figure, axis = plt.subplots(figsize=(11, 5))
    labels = []
    bottoms = [0.0] * len(rows)
    for name, keys in STACK:
        heights = []
        for row in rows:
            heights.append(sum(float(row[k] or 0) for k in keys) / float(row["linear_solve"]))
        axis.bar(range(len(rows)), heights, bottom=bottoms, label=name)
        bottoms = [b + h for b, h in zip(bottoms, heights)]
    rest = [float(r["wall"]) / float(r["linear_solve"]) - b for r, b in zip(rows, bottoms)]
    axis.bar(range(len(rows)), [max(0.0, x) for x in rest], bottom=bottoms, label="process start/exit, other",
             color="lightgrey")
    for row in rows:
        labels.append("%s\n%.2g DOFs" % (row["label"], float(row["dofs"])))
    # The small meshes' ratios (process start-up over milliseconds of solve) would flatten the
    # rest: the axis stops at 8 and every bar is labelled with its ratio.
    for k, row in enumerate(rows):
        ratio = float(row["wall"]) / float(row["linear_solve"])
        axis.text(k, min(ratio, 7.6) + 0.1, "%.2f" % ratio, ha="center", fontsize=7)
    axis.set_ylim(0, 8)
    axis.axhline(1.0, color="black", linewidth=1)
    axis.axhline(2.0, color="black", linewidth=0.8, linestyle="--")
    axis.set_xticks(range(len(rows)))
    axis.set_xticklabels(labels, fontsize=7, rotation=60, ha="right")
    axis.set_ylabel("wall time / one linear solve of K")
    axis.set_title("contactqp solve, process start to exit, per phase (1 = one linear solve, dashed = 2)")
    axis.legend(fontsize=8, ncol=2)
    figure.tight_layout()
    figure.savefig(sys.argv[2], dpi=110)

    with open(sys.argv[3], "w") as out:
        out.write("| run | DOFs | mesh+model | assemble | solve | certify | post-process | write | wall (process) "
                  "| one linear solve | wall / linear | (mesh+assemble) / solve | peak RSS [MiB] | Hertz b err | p0 err | L2 err |\n")
        out.write("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n")
        for r in rows:
            f = lambda k: float(r[k] or 0)  # noqa: E731
            pct = lambda k: ("%+.2f%%" % (100 * float(r[k]))) if r.get(k) else ""  # noqa: E731
            b_error = "hertz_error_half_width" if r.get("hertz_error_half_width") else "hertz_error_contact_radius"
            out.write("| %s | %d | %.3g | %.3g | %.3g | %.3g | %.3g | %.3g | %.3g | %.3g | %.2f× | %.2f | %.0f | %s | %s | %s |\n"
                      % (r["label"] + " " + r["scene"], int(r["dofs"]), f("mesh") + f("model"), f("assemble"),
                         f("contact_solve"), f("certify"), f("postprocess"), f("write"), f("wall"),
                         f("linear_solve"), f("wall") / f("linear_solve"), float(r["mesh_assemble_over_solve"]),
                         f("max_rss_mib"), pct(b_error), pct("hertz_error_max_pressure"),
                         ("%.2f%%" % (100 * f("hertz_error_l2"))) if r.get("hertz_error_l2") else ""))


if __name__ == "__main__":
    main()
