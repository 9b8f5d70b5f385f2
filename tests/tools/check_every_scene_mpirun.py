#!/usr/bin/python3
"""Every shipped scene under `mpirun -n N contactqp solve S --backend petsc --tol 1e-10` against
one process of active_set on the same scene (docs/architecture.md, "Which path a scene takes"):
a scene the run solves gives one process's answer — every contact's force, a or b and p0 (the
one-body contact, each pair), with friction the tangential force (against its contact's normal
force), stick radius or half-width and the stick and slip counts, each reaction (as a vector),
the strain energy and every load step's forces to 1e-8 relative, the error estimate η to 1e-6;
a scene it does not solve yet ends with exit 2 and one line, and is one of REFUSED below (so
that a scene newly refused fails, and a scene newly solved says so). Two derived floating
scenes without equilibrium end as on one process. The large ones ("-large", "-xl") are left to
benchmarks/petsc/.

usage: check_every_scene_mpirun.py CONTACTQP MPIEXEC SCENES_DIR WORKDIR [RANKS [SKIP...]]   (default 2)
SKIP: scenes another ctest entry already runs under mpirun against one process (CI time)."""
import json
import math
import os
import sys

import numpy

from checks import MPI_ENV, Checks, remove_stale, run

TOL = 1e-8
# What the petsc backend does not solve on several processes yet, and the words of its line:
# nothing among the shipped scenes since every one-body scene the distributed run does not model
# (friction, a rigid surface, a body only its contacts hold) takes the problem in parts.
REFUSED = {}

# Scenes run coarser than shipped here, to keep CI short (the same physics: a coarser contact zone).
COARSER = {
    # 125 018 DOFs shipped, about 3 minutes on 2 ranks; 14 200 here.
    "mindlin-spheres.json": lambda scene: [body["mesh"].update(contact_size=0.025) for body in scene["bodies"]],
    # 41 s on 2 ranks shipped (contact_size 3.3e-5); 6 s here.
    "mindlin-force.json": lambda scene: [body["mesh"].update(contact_size=1e-4) for body in scene["bodies"]],
    # The 3D bodies only their contacts hold: 39 855 DOFs shipped, 15 s and 9 s on 2 ranks; 3.5 s
    # and 2.5 s here.
    "hertz-sphere-force.json": lambda scene: scene["body"]["mesh"].update(contact_size=0.03),
    "hertz-sphere-pressure.json": lambda scene: scene["body"]["mesh"].update(contact_size=0.03),
    # 10 s shipped (contact_size 3.3e-5), 4.3 s here.
    "mindlin-on-plane.json": lambda scene: scene["body"]["mesh"].update(contact_size=1e-4),
}


def agree(got, want, key):
    """Whether figure `key` agrees (to TOL; the error estimate to 1e-6). A tangential force is measured against the normal force of the
    same contact or step: the certificate bounds its error by the force scale, and a shear near
    zero (a step that only pushes: Q 7.5e-10 against P 3e-6) has no relative digits of its own."""
    if key not in got:
        return False
    scale = abs(want[key])
    if key.endswith("tangential_force"):
        scale = max(scale, abs(want.get(key[:-len("tangential_force")] + "total_force", 0.0)))
    # η's contact part weighs gaps of round-off size: 1e-6, as check_distributed.py (docs/estimate.md).
    tol = 1e-6 if key.startswith("error_estimate.") else TOL
    # An exact answer (block-moment.json: beam theory, which its elements hold) leaves η at its
    # round-off floor, the square root of round-off in the gaps: below 1e-6 of √(2E) both are zero.
    if key.startswith("error_estimate."):
        floor = 1e-6 * (math.sqrt(2 * want.get("strain_energy", 0.0)) if key.endswith("energy_norm") else 1.0)
        if abs(got[key]) <= floor and abs(want[key]) <= floor:
            return True
    return abs(got[key] - want[key]) <= tol * max(scale, 1e-300)


# With friction, the figures of the tangential side too (the counts compared exactly by agree()).
FIGURES = ("total_force", "half_width", "contact_radius", "max_pressure", "tangential_force", "stick_half_width",
           "stick_radius", "stick_nodes", "slip_nodes")


def numbers(result):
    """The figures a user reads, by name: the contact's and each pair's, reactions, each step's force."""
    out = {}
    for key in FIGURES:
        if isinstance(result["contact"].get(key), (int, float)):
            out["contact." + key] = result["contact"][key]
    for k, pair in enumerate(result.get("pairs", [])):
        for key in FIGURES:
            if isinstance(pair.get(key), (int, float)):
                out["pairs[%d].%s" % (k, key)] = pair[key]
    # The energy and its error estimate (docs/estimate.md), where the run reports them.
    if isinstance(result.get("strain_energy"), (int, float)):
        out["strain_energy"] = result["strain_energy"]
    for key in ("energy_norm", "relative"):
        if isinstance((result.get("error_estimate") or {}).get(key), (int, float)):
            out["error_estimate." + key] = result["error_estimate"][key]
    for k, step in enumerate(result.get("steps", [])):
        for key in ("total_force", "tangential_force", "stick_half_width", "stick_radius"):
            if isinstance(step.get(key), (int, float)):
                out["steps[%d].%s" % (k, key)] = step[key]
    return out


def reactions(result):
    """Each reaction's force vector, by its load (compared as vectors: a component that is zero
    but for round-off has no digits to agree on)."""
    return {r["load"]: numpy.array(r["force"]) for r in result.get("reactions", [])}


def no_equilibrium(cli, mpiexec, scenes, workdir, ranks, env, check):
    """A floating body with no equilibrium under mpirun ends as on one process: exit 1, the line
    naming the body and its motion, the status and a direction of recession in the JSON. The
    roller of two-cylinders-force pulled up, away from every contact; mindlin-force's upper body
    sheared by 1.001 mu P (gross slip, in its last load step)."""
    def pulled(scene):
        scene["bodies"][0]["load"]["value"][1] *= -1

    def beyond_friction(scene):
        COARSER["mindlin-force.json"](scene)
        scene["bodies"][0]["load"][1]["value"][0] = 1.001 * 0.3 * -scene["bodies"][0]["load"][0]["value"][1]

    cases = (("two-cylinders-force.json", pulled, "unbounded: body `roller` moves freely along +y"),
             ("mindlin-force.json", beyond_friction, "unbounded: gross slip: body `upper` slides along +x"))
    for name, change, words in cases:
        with open(os.path.join(scenes, name)) as f:
            scene = json.load(f)
        change(scene)
        derived = os.path.join(workdir, "no-equilibrium-" + name)
        with open(derived, "w") as f:
            json.dump(scene, f)
        mine, theirs = derived + ".mpirun.json", derived + ".one.json"
        remove_stale(mine, theirs)
        code, out, err = run([mpiexec, "-n", ranks, "--oversubscribe", cli, "solve", derived, "--backend", "petsc",
                              "--tol", "1e-10", "--json", mine], env)
        code_one, out_one, err_one = run([cli, "solve", derived, "--backend", "active_set", "--tol", "1e-10",
                                          "--json", theirs], env)
        check(code == 1 and code_one == 1, "%s changed: no equilibrium, exit 1 on %s ranks and on one process "
              "(exit %d, %d)" % (name, ranks, code, code_one))
        check(words in out and words in out_one, "%s changed: the line names the motion, %r" % (name, words))
        if not (os.path.exists(mine) and os.path.exists(theirs)):
            check(False, "%s changed: both runs wrote their JSON" % name)
            continue
        with open(mine) as f:
            result = json.load(f)
        with open(theirs) as f:
            reference = json.load(f)
        d, e = result.get("recession", {}), reference.get("recession", {})
        check(result["status"] == "unbounded" and reference["status"] == "unbounded" and "motion" in e and
              d.get("motion") == e["motion"] and abs(d.get("f_dot_d", 0) - e["f_dot_d"]) <= 1e-6 * abs(e["f_dot_d"]),
              "%s changed: status unbounded, the same recession in both JSON files (%s, f.d %s against %s)"
              % (name, d.get("motion"), d.get("f_dot_d"), e.get("f_dot_d")))


def main(cli, mpiexec, scenes, workdir, ranks="2", *skip):
    os.makedirs(workdir, exist_ok=True)
    env = MPI_ENV
    check = Checks()
    failures = check.failures

    names = sorted(n for n in os.listdir(scenes)
                   if n.endswith(".json") and "-large" not in n and "-xl" not in n and n not in skip)
    solved = []
    for name in names:
        scene = os.path.join(scenes, name)
        if name in COARSER:
            with open(scene) as f:
                coarser = json.load(f)
            COARSER[name](coarser)
            scene = os.path.join(workdir, "coarser-" + name)
            with open(scene, "w") as f:
                json.dump(coarser, f)
        mine, theirs = os.path.join(workdir, name + ".mpirun.json"), os.path.join(workdir, name + ".one.json")
        remove_stale(mine, theirs)
        code, out, err = run([mpiexec, "-n", ranks, "--oversubscribe", cli, "solve", scene, "--backend", "petsc",
                              "--tol", "1e-10", "--quiet", "--json", mine], env)
        lines = [line for line in err.splitlines() if line.startswith("contactqp")]
        if name in REFUSED:
            check(code == 2 and len(lines) == 1 and REFUSED[name] in lines[0] and not os.path.exists(mine),
                  "%s: not solved under mpirun yet, exit %d, %s" % (name, code, lines))
            continue
        check(code == 0, "%s: solved on %s ranks (exit %d) %s" % (name, ranks, code, err.strip()[-300:]))
        if code != 0:
            continue
        code, out, err = run([cli, "solve", scene, "--backend", "active_set", "--tol", "1e-10", "--quiet",
                              "--json", theirs], env)
        check(code == 0, "%s: one process of active_set (exit %d)" % (name, code))
        if code != 0:
            continue
        with open(mine) as f:
            result = json.load(f)
        with open(theirs) as f:
            reference = json.load(f)
        got, want = numbers(result), numbers(reference)
        check(sorted(got) == sorted(want), "%s: the same figures (%d)" % (name, len(want)))
        bad = [key for key in want if key in got and not agree(got, want, key)]
        mine_r, theirs_r = reactions(result), reactions(reference)
        check(sorted(mine_r) == sorted(theirs_r) and all(
            numpy.linalg.norm(mine_r[k] - v) <= TOL * max(numpy.linalg.norm(v), 1e-300) for k, v in theirs_r.items()),
            "%s: the reactions of %s agree to %g" % (name, ", ".join(sorted(theirs_r)), TOL))
        check(not bad, "%s: %d figures agree to %g%s" % (name, len(want), TOL,
                                                          "".join("; %s %.10g against %.10g" % (k, got[k], want[k])
                                                                  for k in bad)))
        solved.append(name)
    # Two bodies with friction and no load steps reach the petsc backend itself under mpirun (the
    # problem in rank shares): one process's answer, the tangential figures included.
    with open(os.path.join(scenes, "mindlin-cylinders.json")) as f:
        scene = json.load(f)
    del scene["steps"]
    scene["bodies"][0]["load"] = {"type": "displacement", "boundary": "top", "value": [3e-6, -2.5e-5]}
    for body in scene["bodies"]:
        body["mesh"]["contact_size"] = 2e-4
    derived = os.path.join(workdir, "two-bodies-friction.json")
    mine, theirs = os.path.join(workdir, "two-bodies.mpirun.json"), os.path.join(workdir, "two-bodies.one.json")
    with open(derived, "w") as f:
        json.dump(scene, f)
    remove_stale(mine, theirs)
    code, out, err = run([mpiexec, "-n", ranks, "--oversubscribe", cli, "solve", derived, "--backend", "petsc",
                          "--tol", "1e-10", "--quiet", "--json", mine], env)
    check(code == 0, "two bodies with friction, no steps: solved on %s ranks (exit %d) %s"
          % (ranks, code, err.strip()[-300:]))
    code_one, out, err = run([cli, "solve", derived, "--backend", "active_set", "--tol", "1e-10", "--quiet",
                              "--json", theirs], env)
    check(code_one == 0, "two bodies with friction, no steps: one process of active_set (exit %d)" % code_one)
    if code == 0 and code_one == 0:
        with open(mine) as f:
            got = numbers(json.load(f))
        with open(theirs) as f:
            want = numbers(json.load(f))
        bad = [key for key in want if not agree(got, want, key)]
        check("pairs[0].tangential_force" in want and not bad,
              "two bodies with friction, no steps: %d figures agree to %g%s" % (
                  len(want), TOL, "".join("; %s %s against %.10g" % (k, got.get(k), want[k]) for k in bad)))
    no_equilibrium(cli, mpiexec, scenes, workdir, ranks, env, check)
    print("solved under mpirun -n %s: %d of %d scenes (%s); not yet: %d" % (
        ranks, len(solved), len(names), ", ".join(solved), len(names) - len(solved)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
