#!/usr/bin/python3
"""ctest entry for `mpirun -n 2 contactqp solve SCENE --backend petsc` (docs/petsc.md): the run
converges, prints its summary once and writes its files once; u and the contact forces agree
with active_set (u <= 1e-6, lambda <= 1e-5, relative 2-norms) and with the same run on one
rank (1e-8); on 2 ranks the run is distributed (each rank holds at most 0.6 of the DOFs, its
ParaView piece in a .pvtu) and the certificate's duality gap is still measured; bad input under
mpirun ends both ranks with exit status 2 and one line: a bad PETSc option, a bad --tol, two
loads a step scales apart.

usage: check_mpirun.py CONTACTQP MPIEXEC SCENE WORKDIR"""
import json
import os
import sys

import numpy
# The two readers alone: `import vtk` loads every VTK module, 0.5 s more per call.
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPUnstructuredGridReader, vtkXMLUnstructuredGridReader

from checks import MPI_ENV, run


def read(path):
    """u and the contact forces at the points, in the order of their coordinates (a .pvtu's
    pieces share the points on their borders: each once)."""
    reader = vtkXMLPUnstructuredGridReader() if path.endswith(".pvtu") else vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    data = grid.GetPointData()
    u, force = vtk_to_numpy(data.GetArray("displacement")), vtk_to_numpy(data.GetArray("contact_force"))
    first = {}
    for k, x in enumerate(map(tuple, vtk_to_numpy(grid.GetPoints().GetData()))):
        first.setdefault(x, k)
    order = [first[x] for x in sorted(first)]
    return u[order].ravel(), force[order].ravel()


def relative(a, b):
    return numpy.linalg.norm(a - b) / max(numpy.linalg.norm(b), 1e-300)


def main(cli, mpiexec, scene, workdir):
    os.makedirs(workdir, exist_ok=True)
    env = MPI_ENV
    mpi = [mpiexec, "-n", "2", "--oversubscribe"]
    failures = []

    def check(condition, text):
        print(("ok   " if condition else "FAIL ") + text)
        if not condition:
            failures.append(text)

    paths = {name: os.path.join(workdir, name + ".vtu") for name in ("active_set", "petsc1")}
    paths["petsc2"] = os.path.join(workdir, "petsc2.pvtu")
    json1, json2 = os.path.join(workdir, "petsc1.json"), os.path.join(workdir, "petsc2.json")
    for path in list(paths.values()) + [json1, json2]:
        if os.path.exists(path):
            os.remove(path)
    code, out, err = run([cli, "solve", scene, "--backend", "active_set", "--tol", "1e-10", "--vtu", paths["active_set"]], env)
    check(code == 0, "active_set converged (exit %d) %s" % (code, err.strip()))
    code, out, err = run([cli, "solve", scene, "--backend", "petsc", "--tol", "1e-10", "--vtu", paths["petsc1"],
                          "--json", json1], env)
    check(code == 0, "petsc on 1 rank converged (exit %d) %s" % (code, err.strip()))
    code, out, err = run(mpi + [cli, "solve", scene, "--backend", "petsc", "--tol", "1e-10", "--vtu", paths["petsc2"],
                               "--json", json2], env)
    check(code == 0, "mpirun -n 2 petsc converged (exit %d) %s" % (code, err.strip()))
    check(out.count("certificate ") == 1, "the summary is printed once (%d times)" % out.count("certificate "))
    leftovers = [name for name in os.listdir(workdir) if ".tmp" in name or name.startswith(".")]
    check(not leftovers, "no temporary files left: %s" % leftovers)
    if os.path.exists(json1) and os.path.exists(json2):
        with open(json1) as one, open(json2) as two:
            result1, result2 = json.load(one), json.load(two)
        whole, share = result2["dofs"], result2["solver"]["dofs_this_rank"]
        print("DOFs: %d in all, %d on rank 0 of 2" % (whole, share))
        check(result2["solver"].get("distributed") == 1, "2 ranks run distributed")
        check(share <= 0.6 * whole, "rank 0 holds at most 0.6 of the DOFs")
        gap1, gap2 = result1["relative_duality_gap"], result2["relative_duality_gap"]
        check(result2["dual_objective"] is not None and abs(gap2) <= 1e-8,
              "the duality gap is measured on 2 ranks (%.2e, 1 rank %.2e)" % (gap2, gap1))
        check(abs(result2["objective"] - result1["objective"]) <= 1e-10 * abs(result1["objective"]),
              "J on 1 and 2 ranks agree to 1e-10")
    if all(os.path.exists(p) for p in paths.values()):
        u_a, l_a = read(paths["active_set"])
        u_1, l_1 = read(paths["petsc1"])
        u_2, l_2 = read(paths["petsc2"])
        print("u: 2 ranks vs active_set %.3e, 1 vs 2 ranks %.3e" % (relative(u_2, u_a), relative(u_2, u_1)))
        print("lambda: 2 ranks vs active_set %.3e, 1 vs 2 ranks %.3e" % (relative(l_2, l_a), relative(l_2, l_1)))
        check(relative(u_2, u_a) <= 1e-6, "u agrees with active_set to 1e-6")
        check(relative(l_2, l_a) <= 1e-5, "lambda agrees with active_set to 1e-5")
        check(relative(u_2, u_1) <= 1e-8, "u on 1 and 2 ranks agree to 1e-8")
        check(relative(l_2, l_1) <= 1e-8, "lambda on 1 and 2 ranks agree to 1e-8")
    # Bad input found after PETSc started (on every rank): exit 2, one line for the run.
    code, out, err = run(mpi + [cli, "solve", scene, "--backend", "petsc", "--petsc-options=-ksp_type no_such_ksp"], env)
    # mpirun adds its own notice of a non-zero exit; contactqp's part is one line.
    lines = [line for line in err.splitlines() if line.startswith("contactqp")]
    check(code == 2, "a bad PETSc option under mpirun exits 2 (got %d)" % code)
    check(len(lines) == 1 and "petsc_options" in lines[0], "one line names petsc_options: %s" % lines)
    # Bad input found before (the same on every rank): exit 2, one line.
    code, out, err = run(mpi + [cli, "solve", scene, "--backend", "petsc", "--tol", "7"], env)
    lines = [line for line in err.splitlines() if line.startswith("contactqp")]
    check(code == 2 and len(lines) == 1 and "--tol" in lines[0], "bad --tol under mpirun: exit %d, %s" % (code, lines))
    # (Load steps of two bodies, with friction, are solved on several processes and compared with
    # one process by check_every_scene_mpirun.py: mindlin-cylinders, mindlin-spheres.)
    # Two loads that a step scales apart on the same DOFs, found by the ranks that hold those
    # nodes: every rank ends with exit 2 and one line naming the step, no file.
    with open(scene) as f:
        text = json.load(f)
    if text.get("model") == "plane_strain" and "bodies" not in text:
        push = dict(text["load"] if isinstance(text["load"], dict) else text["load"][0])
        text["load"] = [dict(push, name="a"), dict(push, name="b")]
        text["steps"] = [{"factors": {"a": 1, "b": 1}}, {"factors": {"b": 0.5}}]
        conflicting = os.path.join(workdir, "conflicting-steps.json")
        with open(conflicting, "w") as f:
            json.dump(text, f)
        out_json = os.path.join(workdir, "conflicting.json")
        code, out, err = run(mpi + [cli, "solve", conflicting, "--backend", "petsc", "--json", out_json], env)
        lines = [line for line in err.splitlines() if line.startswith("contactqp")]
        check(code == 2 and len(lines) == 1 and "steps[1] prescribes the node at" in lines[0]
              and not os.path.exists(out_json), "steps scaling two loads apart under mpirun: exit %d, %s" % (code, lines))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:5]))
