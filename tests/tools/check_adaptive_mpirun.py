#!/usr/bin/python3
"""An adaptive run (docs/adaptive.md) under `mpirun -n N` against the same run on one process:
every rank runs the same cycles on the same meshes, the petsc backend on the problem in parts.
Two coarse scenes: one body on a plane (which the distributed run would otherwise take) and two
cylinders, both meshes adapted. The cycles must be the same (elements and DOFs exactly, the
estimate to 1e-6) and the last mesh's answer the same (force, b and p0 to 1e-8); the exit status
and whether the target was met too.

usage: check_adaptive_mpirun.py CONTACTQP MPIEXEC WORKDIR [RANKS]   (default 2)"""
import json
import os
import sys

from checks import MPI_ENV, Checks, remove_stale, run

ONE_BODY = {
    "model": "plane_strain", "material": {"E": 1.0, "nu": 0.3},
    "body": {"shape": "half_disc", "radius": 1.0, "symmetry": True,
             "mesh": {"size": 0.25, "contact_size": 0.25}},
    "load": {"type": "displacement", "boundary": "top", "value": [None, -0.016]},
    "obstacle": {"type": "plane", "point": [0.0, 0.0], "normal": [0.0, 1.0]},
    "solver": {"backend": "petsc", "tol": 1e-10},
    "adapt": {"target": 0.05},
}

TWO_BODIES = {
    "model": "plane_strain",
    "bodies": [
        {"name": "upper", "shape": "half_disc", "radius": 1.0, "mesh": {"size": 0.25, "contact_size": 0.25},
         "material": {"E": 1.0, "nu": 0.3},
         "load": {"type": "displacement", "boundary": "top", "value": [0.0, -0.01]}},
        {"name": "lower", "shape": "half_disc", "radius": 1.0, "mirror": True,
         "mesh": {"size": 0.25, "contact_size": 0.25}, "material": {"E": 1.0, "nu": 0.3},
         "load": {"type": "displacement", "boundary": "top", "value": [0.0, 0.0]}},
    ],
    "contact": {"pair": ["upper.arc", "lower.arc"]},
    "solver": {"backend": "petsc", "tol": 1e-10},
    "adapt": {"target": 0.06},
}


def close(a, b, tol):
    return abs(a - b) <= tol * max(abs(b), 1e-300)


def answer(result):
    """The last mesh's contact: the one body's, or the first pair's."""
    contact = result["pairs"][0] if result.get("pairs") else result["contact"]
    return {key: contact[key] for key in ("total_force", "half_width", "max_pressure")
            if isinstance(contact.get(key), (int, float))}


def main(cli, mpiexec, workdir, ranks="2"):
    os.makedirs(workdir, exist_ok=True)
    check = Checks()
    for name, scene in (("one-body", ONE_BODY), ("two-bodies", TWO_BODIES)):
        path = os.path.join(workdir, name + ".json")
        with open(path, "w") as f:
            json.dump(scene, f)
        mine, theirs = os.path.join(workdir, name + ".mpirun.json"), os.path.join(workdir, name + ".one.json")
        remove_stale(mine, theirs)
        code, out, err = run([mpiexec, "-n", ranks, "--oversubscribe", cli, "solve", path, "--quiet", "--json", mine],
                             MPI_ENV)
        code_one, out, err_one = run([cli, "solve", path, "--quiet", "--json", theirs], MPI_ENV)
        check(code == 0 and code_one == 0, "%s: the adaptive run on %s ranks and on one process (exit %d, %d) %s %s"
              % (name, ranks, code, code_one, err.strip()[-300:], err_one.strip()[-300:]))
        if code != 0 or code_one != 0:
            continue
        with open(mine) as f:
            got = json.load(f)
        with open(theirs) as f:
            want = json.load(f)
        cycles, reference = got["adaptive"]["cycles"], want["adaptive"]["cycles"]
        check(len(reference) >= 3 and got["adaptive"]["met"] == want["adaptive"]["met"] is True,
              "%s: the target met on both, after %d cycles (at least 3)" % (name, len(reference)))
        same = len(cycles) == len(reference) and all(
            a["elements"] == b["elements"] and a["dofs"] == b["dofs"] and close(a["relative"], b["relative"], 1e-6)
            for a, b in zip(cycles, reference))
        check(same, "%s: the same cycles (elements, DOFs; estimate to 1e-6): %s against %s" % (
            name, [(c["dofs"], c["relative"]) for c in cycles], [(c["dofs"], c["relative"]) for c in reference]))
        a, b = answer(got), answer(want)
        check(len(b) == 3 and sorted(a) == sorted(b) and all(close(a[k], b[k], 1e-8) for k in b),
              "%s: the last mesh's force, b and p0 agree to 1e-8: %s against %s" % (name, a, b))
    return 1 if check.failures else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
