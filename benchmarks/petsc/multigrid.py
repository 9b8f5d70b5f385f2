#!/usr/bin/python3
"""The PETSc solver of K and the petsc backend's contact solve, before and after the multigrid
work of docs/petsc-measurements.md ("The preconditioner", "The contact solve"), in one run so that the ratios
compare on a shared machine. On one scene (default scenes/hertz-sphere-large.json), RANKS ranks:

  before / after, whole run     [mpirun -n RANKS] contactqp solve SCENE --backend petsc
  before / after, K alone       ... --no-contact --linear-solver petsc
  solvers of K (after build)    ... --no-contact --linear-solver petsc --petsc-options=...
                                (P1 + GAMG, the default for quadratic elements; GAMG tuned,
                                on K itself; GAMG with PETSc's defaults; hypre BoomerAMG, plain
                                and nodal with interpolation vectors; ML; for quadratic
                                elements the P1 level with BoomerAMG or ML below it)

Each run under /usr/bin/time (peak resident set per rank). Prints one table: whole seconds,
set-up (the preconditioner's, or the solver of K's), the solve, CG iterations, preconditioner
set-ups, for the contact runs the contact solve over the same build's linear solve, and the
hierarchy's levels, grid and operator complexity (GAMG, ML and PCMG report them; hypre not).

usage: benchmarks/petsc/multigrid.py AFTER_BUILD [BEFORE_BUILD] [--scene S] [--ranks N] [--out DIR]
       [--only contact|solvers]
Heavy (at 1.34e6 DOFs: 7 GB per rank before, about 20 runs of 1-5 minutes): run it on a quiet
machine."""
import argparse
import json
import os
import subprocess
import sys
import time

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# The solvers of K compared (docs/petsc-design.md, "The preconditioner"); empty: the build's default.
HYPRE = ("-pc_hypre_type boomeramg -pc_hypre_boomeramg_strong_threshold 0.5 -pc_hypre_boomeramg_coarsen_type HMIS "
         "-pc_hypre_boomeramg_interp_type ext+i -pc_hypre_boomeramg_agg_nl 1 -pc_hypre_boomeramg_P_max 4")
# BoomerAMG's systems options: nodal coarsening, and the rigid-body modes (the near-null space
# contactqp sets) as interpolation vectors.
NODAL = " -pc_hypre_boomeramg_nodal_coarsen 6 -pc_hypre_boomeramg_vec_interp_variant 3"
SOLVERS = [
    ("default (P1 + GAMG for quadratic elements)", ""),
    ("GAMG tuned, on K", "-pc_type gamg -pc_gamg_threshold 0.02 -pc_gamg_aggressive_coarsening 2 "
                         "-pc_gamg_coarse_eq_limit 200 -pc_gamg_use_sa_esteig 0 -mg_levels_ksp_type chebyshev "
                         "-mg_levels_pc_type jacobi -mg_levels_esteig_ksp_type cg"),
    ("GAMG, PETSc's defaults", "-pc_type gamg"),
    ("hypre BoomerAMG", "-pc_type hypre " + HYPRE),
    ("hypre BoomerAMG, nodal + interpolation vectors", "-pc_type hypre " + HYPRE + NODAL),
    ("ML", "-pc_type ml -pc_ml_Threshold 0.02 -mg_levels_ksp_type chebyshev -mg_levels_pc_type jacobi"),
]
# Quadratic elements only: other AMGs below the P1 level (the P1 operator has block size dim,
# so BoomerAMG's nodal coarsening sees whole vertices).
P1_SOLVERS = [
    ("P1 level + hypre BoomerAMG, nodal + interpolation vectors",
     "-mg_coarse_pc_type hypre " + (HYPRE + NODAL).replace("-pc_hypre", "-mg_coarse_pc_hypre")),
    ("P1 level + ML", "-mg_coarse_pc_type ml -mg_coarse_pc_ml_Threshold 0.02"),
]


def run(build, scene, ranks, out, name, extra, backend="petsc"):
    """One contactqp run; returns (its JSON, wall seconds, peak MB of the largest rank)."""
    json_path = os.path.join(out, name + ".json")
    time_prefix = os.path.join(out, name + "-time")
    command = ["/bin/sh", "-c", 'exec /usr/bin/time -f %M -o "$0-${OMPI_COMM_WORLD_RANK:-0}.txt" "$@"', time_prefix,
               os.path.join(build, "contactqp"), "solve", scene, "--backend", backend, "--json", json_path,
               "--quiet"] + extra
    if ranks > 1:
        command = ["mpirun", "-n", str(ranks), "--oversubscribe"] + command
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    if os.path.exists(json_path):
        os.remove(json_path)  # a failed run must not read an earlier run's result
    start = time.monotonic()
    done = subprocess.run(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wall = time.monotonic() - start
    with open(os.path.join(out, name + ".txt"), "w") as log:
        log.write(done.stdout)
    peak = 0.0
    for rank in range(ranks):
        try:
            with open("%s-%d.txt" % (time_prefix, rank)) as f:
                peak = max(peak, float(f.read().split()[-1]) / 1024)
        except (OSError, ValueError, IndexError):
            pass
    try:
        with open(json_path) as f:
            return json.load(f), wall, peak
    except (OSError, ValueError):
        return None, wall, peak


def figures(result):
    """The columns of the table from a result JSON (None: the run failed)."""
    if result is None:
        return None
    timings, solver = result.get("timings", {}), result.get("solver", {})
    return {
        "status": result.get("status", "?"),
        "total": timings.get("total", 0.0),
        "setup": solver.get("preconditioner_setup_seconds", timings.get("factorize", 0.0)),
        # The matrix into PETSc, the preconditioner's set-ups and the iterations (K alone: the
        # solver of K's set-up and its one solve).
        "solve": timings.get("factorize", 0.0) + timings.get("solve", 0.0),
        "certify": timings.get("certify", 0.0),
        "cg": solver.get("krylov_iterations", result.get("iterations", 0)),
        "setups": solver.get("preconditioner_setups", 1),
        "p0": (result.get("hertz") or {}).get("p0_numerical"),
        "levels": solver.get("multigrid_levels"),
        "grid": solver.get("grid_complexity"),
        "operator": solver.get("operator_complexity"),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("after")
    parser.add_argument("before", nargs="?")
    parser.add_argument("--scene", default=os.path.join(SOURCE, "scenes", "hertz-sphere-large.json"))
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--out", default=os.path.join(SOURCE, "benchmarks", "petsc", "results", "multigrid"))
    parser.add_argument("--only", choices=["contact", "solvers"])
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = []
    if args.only != "solvers":
        for label, build in (("before", args.before), ("after", args.after)):
            if not build:
                continue
            contact = run(build, args.scene, args.ranks, args.out, label + "-contact", [])
            linear = run(build, args.scene, args.ranks, args.out, label + "-K",
                         ["--no-contact", "--linear-solver", "petsc"])
            rows.append((label + ": contact run", contact, linear))
            rows.append((label + ": K alone", linear, None))
    if args.only != "contact":
        solvers = list(SOLVERS)
        for k in range(len(SOLVERS) + len(P1_SOLVERS)):
            if k >= len(solvers):
                break
            label, options = solvers[k]
            extra = ["--no-contact", "--linear-solver", "petsc"]
            if options:
                extra.append("--petsc-options=" + options)
            row = run(args.after, args.scene, args.ranks, args.out, "solver-%d" % k, extra)
            rows.append(("K: " + label, row, None))
            if k == 0 and row[0] and row[0].get("element_order") == 2:
                solvers += P1_SOLVERS

    print("%s, %d ranks, seconds. solve: matrix into PETSc + preconditioner set-up(s) + iterations (K alone: "
          "the solver of K's set-up + its solve); setup: the preconditioner's (K alone and before: with the matrix "
          "copy); contact/linear: the contact run's solve over the same build's K-alone solve"
          % (os.path.basename(args.scene), args.ranks))
    print("| run | status | wall | total | setup | solve | certify | CG its | PC set-ups | contact/linear | "
          "levels | grid cx | operator cx | peak MB/rank |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for label, (result, wall, peak), linear in rows:
        f = figures(result)
        if f is None:
            print("| %s | failed (see %s) | %.1f | | | | | | | | | | | %.0f |" % (label, args.out, wall, peak))
            continue
        ratio = ""
        g = figures(linear[0]) if linear else None
        if g and g["solve"] > 0:
            ratio = "%.2f" % (f["solve"] / g["solve"])
        complexity = ["%d" % f["levels"] if f["levels"] else "–"] + \
            ["%.2f" % f[key] if f[key] else "–" for key in ("grid", "operator")]
        print("| %s | %s | %.1f | %.1f | %.1f | %.1f | %.1f | %s | %s | %s | %s | %.0f |" %
              (label, f["status"], wall, f["total"], f["setup"], f["solve"], f["certify"], int(f["cg"]),
               int(f["setups"]), ratio, " | ".join(complexity), peak))
    return 0


if __name__ == "__main__":
    sys.exit(main())
