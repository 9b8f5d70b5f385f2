#!/usr/bin/python3
"""Memory per rank of the distributed run (docs/petsc-measurements.md, "Distributed runs"): one scene solved
by the petsc backend on 1, 2, 4, 8 ranks (the distributed path, --distributed on one rank;
--oversubscribe beyond the cores), each rank under /usr/bin/time -v (its peak resident set) and
--phase-memory (its peak in each phase and its resident memory when each phase starts). From
those, per rank and phase:

  mesh           the mesh phase's peak (rank 0 meshes the coarse body with Gmsh)
  model          what the model phase adds to what the mesh left
  matrices       what assembly leaves held: PETSc's A (and f, b)
  solver         the solve's peak above the assembled state: W, the multigrid hierarchy, vectors
                 (PETSc's own MatGetInfo figures from the result JSON beside it)
  certify        the certificate's one solve
  output         post-processing and the write, above what they start from
  peak           the process's peak (time -v)

Writes OUT/memory.csv (one row per rank and run), OUT/memory-table.md, OUT/context.json and each
run's JSON and stderr (OUT/RANKS/). Ranks whose run did not finish keep their row with the status.

usage: benchmarks/petsc/memory.py BUILD_DIR SCENE OUT_DIR [RANKS...]      (default 1 2 4 8)
       benchmarks/petsc/memory.py - SCENE OUT_DIR RANKS...     (the table again from OUT_DIR's runs)
Run it under flock /work/coord/heavy.lock when the scene needs more than 3 GB."""
import csv
import datetime
import json
import os
import re
import subprocess
import sys

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")
FIELDS = ["ranks", "rank", "status", "dofs", "dofs_this_rank", "wall_s", "peak_mib", "mesh_mib", "model_mib",
          "matrices_mib", "solver_mib", "certify_mib", "output_mib", "petsc_matrix_mib", "petsc_total_mib",
          "bytes_per_dof_sum"]


def phases(line):
    return {name: float(value) for name, value in re.findall(r"(\w+) ([\d.]+)", line)}


def parse_stderr(text):
    """Each rank's peaks and phase-start memory from --phase-memory's lines."""
    out = {}
    for kind, key in (("peak", r"peak memory"), ("start", r"memory at phase start")):
        for match in re.finditer(key + r" \[MiB\](?: \(rank (\d+)\))?: (.*)", text):
            rank = int(match.group(1) or 0)
            out.setdefault(rank, {})[kind] = phases(match.group(2))
    return out


def split(peak, start):
    """A rank's memory by what holds it (MiB)."""
    def held(after):
        return start.get(after, 0.0)
    return {
        "mesh_mib": peak.get("mesh", 0.0),
        "model_mib": max(0.0, held("assemble") - held("model")),
        "matrices_mib": max(0.0, held("solve") - held("assemble")),
        "solver_mib": max(0.0, peak.get("solve", 0.0) - held("solve")),
        "certify_mib": max(0.0, peak.get("certify", 0.0) - held("certify")),
        "output_mib": max(0.0, max(peak.get("postprocess", 0.0), peak.get("write", 0.0)) - held("postprocess")),
    }


def run(cli, scene, ranks, out):
    directory = os.path.join(out, str(ranks))
    os.makedirs(directory, exist_ok=True)
    result = os.path.join(directory, "result.json")
    times = os.path.join(directory, "time")
    if os.path.exists(result):
        os.remove(result)
    inner = ["/bin/sh", "-c", 'exec /usr/bin/time -v -o "%s.${OMPI_COMM_WORLD_RANK:-0}" "$@"' % times, "sh", cli,
             "solve", scene, "--backend", "petsc", "--json", result, "--quiet", "--phase-memory"]
    if ranks == 1:
        inner.append("--distributed")
    command = ["mpirun", "-n", str(ranks), "--oversubscribe"] + inner
    done = subprocess.run(command, env=ENV, capture_output=True, text=True)
    with open(os.path.join(directory, "stderr.txt"), "w") as f:
        f.write(done.stderr)
    with open(os.path.join(directory, "exit"), "w") as f:
        f.write("%d\n" % done.returncode)
    return collect(out, ranks)


def collect(out, ranks):
    """The rows of one run from the files it left in OUT/RANKS/."""
    directory = os.path.join(out, str(ranks))
    result = os.path.join(directory, "result.json")
    times = os.path.join(directory, "time")
    report = json.load(open(result)) if os.path.exists(result) else {}
    stderr = open(os.path.join(directory, "stderr.txt")).read() if os.path.exists(
        os.path.join(directory, "stderr.txt")) else ""
    code = open(os.path.join(directory, "exit")).read().strip() if os.path.exists(
        os.path.join(directory, "exit")) else "?"
    memory = parse_stderr(stderr)
    rows = []
    for rank in range(ranks):
        row = {"ranks": ranks, "rank": rank, "status": report.get("status", "exit " + code)}
        try:
            text = open("%s.%d" % (times, rank)).read()
            row["peak_mib"] = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", text).group(1)) / 1024
            wall = re.search(r"Elapsed \(wall clock\) time.*: (?:(\d+):)?(\d+):([\d.]+)", text)
            row["wall_s"] = int(wall.group(1) or 0) * 3600 + int(wall.group(2)) * 60 + float(wall.group(3))
        except (OSError, AttributeError):
            pass
        if rank in memory and "peak" in memory[rank] and "start" in memory[rank]:
            row.update(split(memory[rank]["peak"], memory[rank]["start"]))
        solver = report.get("solver", {})
        row["dofs"] = report.get("dofs")
        row["petsc_matrix_mib"] = solver.get("petsc_matrix_mb_per_rank")
        row["petsc_total_mib"] = solver.get("petsc_memory_mb_per_rank")
        if rank == 0:
            row["dofs_this_rank"] = solver.get("dofs_this_rank")
        rows.append(row)
    total = sum(r.get("peak_mib", 0) for r in rows)
    for r in rows:
        if r.get("dofs"):
            r["bytes_per_dof_sum"] = total * 1048576 / r["dofs"]
    return rows


def table(rows):
    lines = ["| ranks | rank | peak [MiB] | mesh | model | A (assembled) | solve above it | certify | output | "
             "PETSc A / all [MiB] | sum of peaks per DOF |",
             "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|"]
    fmt = lambda x: "%.0f" % x if isinstance(x, (int, float)) else "–"
    for r in rows:
        per_dof = "%.2f KB" % (r["bytes_per_dof_sum"] / 1000) if r.get("bytes_per_dof_sum") and r["rank"] == 0 else ""
        lines.append("| %d | %d | %s | %s | %s | %s | %s | %s | %s | %s / %s | %s |" % (
            r["ranks"], r["rank"], fmt(r.get("peak_mib")), fmt(r.get("mesh_mib")), fmt(r.get("model_mib")),
            fmt(r.get("matrices_mib")), fmt(r.get("solver_mib")), fmt(r.get("certify_mib")), fmt(r.get("output_mib")),
            fmt(r.get("petsc_matrix_mib")), fmt(r.get("petsc_total_mib")), per_dof))
    return "\n".join(lines) + "\n"


def main(build, scene, out, *ranks):
    """With BUILD_DIR "-" nothing runs: the table is made again from the runs OUT holds."""
    cli = os.path.join(os.path.abspath(build), "contactqp")
    os.makedirs(out, exist_ok=True)
    rows = []
    for n in [int(r) for r in ranks] or [1, 2, 4, 8]:
        rows += collect(out, n) if build == "-" else run(cli, os.path.abspath(scene), n, out)
        print(table([r for r in rows if r["ranks"] == n]), flush=True)
    with open(os.path.join(out, "memory.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=FIELDS)
        writer.writeheader()
        for r in rows:
            writer.writerow({k: r.get(k, "") for k in FIELDS})
    with open(os.path.join(out, "memory-table.md"), "w") as f:
        f.write(table(rows))
    revision = subprocess.run(["git", "-C", SOURCE, "rev-parse", "--short", "HEAD"], capture_output=True,
                              text=True).stdout.strip()
    json.dump({"command": "benchmarks/petsc/memory.py " + " ".join([build, scene, out] + list(ranks)),
               "date": datetime.date.today().isoformat(), "revision": revision, "cores": os.cpu_count(),
               "scene": scene}, open(os.path.join(out, "context.json"), "w"), indent=2)


if __name__ == "__main__":
    main(*sys.argv[1:])
