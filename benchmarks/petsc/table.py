#!/usr/bin/python3
"""The table of docs/petsc-measurements.md, "Time and memory per rank", from run.py's CSV.

usage: benchmarks/petsc/table.py OUT/petsc.csv

One block of rows per level: active_set and one solve on CHOLMOD, the petsc backend with the
default and the best options on 1 and 2 ranks, one solve with PETSc's KSP (--linear-solver
petsc) and one by the petsc backend's run (--backend petsc --no-contact) on 1 and 2 ranks."""
import csv
import sys


def significant(x, digits=3):
    """x to `digits` significant digits, as the docs print it ('' when missing)."""
    if x in (None, ""):
        return ""
    value = float(x)
    return "%.*g" % (digits, value) if value < 10 ** digits else "%d" % round(value)


def dofs_label(level, dofs):
    mantissa, exponent = ("%.2e" % float(dofs)).split("e")
    return "%s %se%d" % (level.split(":")[0].upper(), mantissa, int(exponent))


def cell(rows, key, fmt=significant):
    """One value, or 'a / b' for the 1- and 2-rank runs of one configuration ('' when none has one)."""
    if all(row[key] in (None, "") for row in rows):
        return ""
    return " / ".join(fmt(row[key]) for row in rows)


def status(rows):
    """'converged, 9' or 'converged, 9 / 8' (outer steps); '' for a linear solve."""
    if rows[0]["backend"] == "one solve":
        return ""
    states = list(dict.fromkeys(row["status"] for row in rows))
    steps = " / ".join(row["iterations"] for row in rows)
    return "%s, %s" % (states[0], steps) if len(states) == 1 else " / ".join(
        "%s, %s" % (row["status"], row["iterations"]) for row in rows)


def main(path):
    rows = list(csv.DictReader(open(path)))
    levels = list(dict.fromkeys(row["level"] for row in rows))
    print("| DOFs | run | ranks | status, outer steps | Krylov | solver s | PETSc MiB/rank | peak MiB/rank |")
    print("|---|---|---|---|---|---|---|---|")
    for level in levels:
        at = [row for row in rows if row["level"] == level]

        def runs(backend, options, ranks):
            return [row for row in at if row["backend"] == backend and row["options"] == options
                    and int(row["ranks"]) in ranks]

        lines = [
            ("active_set (CHOLMOD)", runs("active_set", "cholmod", (1,))),
            ("one solve (CHOLMOD)", runs("one solve", "cholmod", (1,))),
            ("petsc default", runs("petsc", "default", (1,))),
            ("petsc default", runs("petsc", "default", (2,))),
            ("petsc best", runs("petsc", "best", (1, 2))),
            ("one solve (PETSc KSP)", runs("one solve", "petsc", (1, 2))),
            ("one solve (petsc run)", runs("one solve", "petsc backend", (1, 2))),
        ]
        first = True
        for name, group in lines:
            if not group:
                continue
            label = dofs_label(level, group[0]["dofs"]) if first else ""
            first = False
            cholmod = "CHOLMOD" in name
            print("| %s | %s | %s | %s | %s | %s | %s | %s |" % (
                label, name, " / ".join(row["ranks"] for row in group), status(group),
                "–" if cholmod else cell(group, "krylov_iterations", lambda x: x),
                cell(group, "solver_seconds"),
                "–" if cholmod else cell(group, "petsc_mib_per_rank", lambda x: significant(x, 4)),
                cell(group, "peak_mib_per_rank", lambda x: "%d" % round(float(x)) if x else "")))


if __name__ == "__main__":
    main(sys.argv[1])
