#!/usr/bin/python3
"""Hertz's cylinder solved by GetFEM: the peer that contactqp is measured against.

The problem is the one of contactqp's scenes/hertz.json. Plane strain; the body is the lower half
of the disc of radius R centred at (0, R); its flat cut y = R is displaced by (free, -delta), i.e.
u_y = -delta and u_x free there; a rigid plane y = 0 lies below. With --symmetry only x >= 0 is
modelled, with u_x = 0 on x = 0 (otherwise u_x is pinned at the cut's midpoint (0, R), which
removes the sliding mode and carries no force by symmetry).

Mesh: the same as contactqp's (src/mesh/half_disc_mesher.cpp, src/model/model.cpp): the geometry
in units of R, the arc split where contact can happen (the facing points whose initial gap is at
most 1.5 delta, widened by one contact_size), a Distance field on that arc and the MathEval size
field Min(size, contact_size + grading * distance), Frontal-Delaunay (algorithm 6), written as a
.geo and meshed by the gmsh command-line tool, then scaled by R. The .msh (format 2.2 ASCII,
physical groups "arc", "top", "symmetry" (curves) and "body" (surface)) can be kept with --msh so
that contactqp can be run on exactly the same mesh. (Format 2.2 because GetFEM 5.4 imports a 4.1
file with a physical group of two curves as two regions.)

Formulation (default --formulation integral), GetFEM's "weak integral contact condition" with a
rigid obstacle, the one its user documentation presents as the scalable one and its own demo
(demo_static_contact.py) uses: Model.add_integral_contact_with_rigid_obstacle_brick with option 1,
the non-symmetric Alart-Curnier augmented Lagrangian. The contact stress lambda_n is a P1 (P2 with
--order 2) field on the candidate part of the arc; the obstacle is the signed distance y; the
condition is

    int_Gc (lambda_n + (lambda_n - r (u_N - gap))_-) mu dGamma = 0   for all mu,

solved together with elasticity by GetFEM's semi-smooth Newton method (Model.solve, MUMPS). The
augmentation r is taken as E, as the documentation advises ("chosen close to the Young modulus");
the discrete solution does not depend on it (README: P changes by 5e-8 relative for r/E from 0.1
to 100). The Dirichlet conditions are normal-component conditions with P1 multipliers
(add_normal_Dirichlet_condition_with_multipliers), exact at the nodes of the straight boundaries.

Alternatives: --formulation nodal (add_nodal_contact_with_rigid_obstacle_brick: one multiplier per
node, nodal Alart-Curnier, the same discrete problem as contactqp's) and --formulation nitsche
(add_Nitsche_contact_with_rigid_obstacle_brick, no multiplier; GetFEM's parameter gamma = gamma0 h
with gamma0 = --param / E, default 1; --theta, default 0: theta = 1 did not converge here).

Post-processing, identical to contactqp's (src/post/): the nodal contact force at an arc node is
the elastic reaction F_i = (K u)_y there (by equilibrium, what the contact term exerts, whatever
the formulation); the pressure is F_i over the node's tributary length int_arc phi_i ds (contactqp's
lambda_i / w_i). Total force P = sum F_i (doubled with symmetry), half-width b = 2 sqrt(sum F x^2 /
sum F) (x from the centre of pressure), p0 = the largest nodal pressure, and the L2 error of the
piecewise linear nodal pressure against Hertz's p(x) = p0 sqrt(1 - x^2/b^2) for the computed P
(b = sqrt(4PR/(pi E*)), p0 = 2P/(pi b), E* = E/(1 - nu^2)), relative to ||p_Hertz||.

Timing: `seconds` is the wall time of GetFEM's model set-up, assembly and Newton solve (the
fastest of --repeat runs in one process, all in `seconds_all`; `seconds_newton` is the part spent
in Model.solve, which assembles and factors the tangent system at every iteration); mesh
generation plus import (`seconds_mesh`), module import (`seconds_import`) and post-processing
(`seconds_post`) are reported separately.

Run with Debian's /usr/bin/python3 (python3-getfem, numpy) and the gmsh command on PATH.
Exit status: 0 converged, 1 not converged or a tool failed, 2 bad arguments.
"""

import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

START = time.perf_counter()

# Candidate contact nodes: initial gap at most this many times the prescribed displacement
# (contactqp's kLoadGapFactor, src/model/model.cpp).
LOAD_GAP_FACTOR = 1.5
# Physical group tags written into the .geo; the names are the contract with contactqp's reader.
GROUPS = {"arc": (1, 1), "top": (1, 2), "symmetry": (1, 3), "body": (2, 4)}
FORMULATIONS = ("integral", "nodal", "nitsche")
# Gauss-Legendre, 8 points on [-1, 1] (as contactqp's src/post/hertz.cpp).
GAUSS_X = (-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
           0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363)
GAUSS_W = (0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
           0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763)
TRIANGLE_AREA = 0.4330127018922193  # area of an equilateral triangle of side h is this times h^2


class BadArgument(Exception):
    pass


class ToolFailure(Exception):
    pass


def parse_args(argv):
    parser = argparse.ArgumentParser(
        description="Hertz's cylinder on a rigid plane, solved by GetFEM on contactqp's mesh.")
    parser.add_argument("--radius", type=float, required=True, help="R (length)")
    parser.add_argument("--E", type=float, required=True, help="Young's modulus")
    parser.add_argument("--nu", type=float, required=True, help="Poisson's ratio")
    parser.add_argument("--delta", type=float, required=True, help="downward displacement of the cut (length)")
    parser.add_argument("--size", type=float, required=True, help="element size far from the contact (length)")
    parser.add_argument("--contact-size", type=float, required=True, help="element size along the contact arc")
    parser.add_argument("--grading", type=float, default=0.1, help="size growth per unit distance, (0, 1]")
    parser.add_argument("--symmetry", action="store_true", help="model x >= 0 only, u_x = 0 on x = 0")
    parser.add_argument("--order", type=int, default=1, help="1 (P1 triangles) or 2 (P2)")
    parser.add_argument("--formulation", default="integral", help="integral (default), nodal or nitsche")
    parser.add_argument("--param", type=float, default=1.0,
                        help="r/E (integral, nodal) or gamma0*E (nitsche); default 1")
    parser.add_argument("--theta", type=float, default=0.0, help="Nitsche's theta (nitsche only); default 0")
    parser.add_argument("--tol", type=float, default=1e-9, help="Newton residual target (GetFEM max_res)")
    parser.add_argument("--max-iter", type=int, default=100, help="Newton iteration limit")
    parser.add_argument("--repeat", type=int, default=1,
                        help="solve this many times in one process and report the fastest (noisy machines)")
    parser.add_argument("--max-elements", type=int, default=2000000, help="refuse larger meshes")
    parser.add_argument("--out", required=True, help="result JSON")
    parser.add_argument("--msh", help="keep the mesh here (.msh, with the .geo beside it)")
    args = parser.parse_args(argv)

    def require(ok, option, value, what):
        if not ok:
            raise BadArgument(f"{option} = {value!r} {what}")

    for option in ("radius", "E", "delta", "size", "contact_size", "param", "tol"):
        value = getattr(args, option)
        require(math.isfinite(value) and value > 0, "--" + option.replace("_", "-"), value, "must be a positive number")
    require(math.isfinite(args.nu) and -1 < args.nu < 0.5, "--nu", args.nu, "must lie in (-1, 0.5)")
    require(args.delta < args.radius, "--delta", args.delta, f"must be smaller than --radius ({args.radius})")
    require(args.contact_size <= args.size, "--contact-size", args.contact_size, f"must not exceed --size ({args.size})")
    require(args.size <= args.radius, "--size", args.size, f"must not exceed --radius ({args.radius})")
    require(math.isfinite(args.grading) and 0 < args.grading <= 1, "--grading", args.grading, "must lie in (0, 1]")
    require(args.order in (1, 2), "--order", args.order, "must be 1 or 2")
    require(args.formulation in FORMULATIONS, "--formulation", args.formulation, "must be one of " + ", ".join(FORMULATIONS))
    require(math.isfinite(args.theta), "--theta", args.theta, "must be a number")
    require(args.max_iter >= 1, "--max-iter", args.max_iter, "must be at least 1")
    require(args.repeat >= 1, "--repeat", args.repeat, "must be at least 1")
    require(args.max_elements >= 1, "--max-elements", args.max_elements, "must be at least 1")
    for option, path in (("--out", args.out), ("--msh", args.msh)):
        if path is None:
            continue
        folder = os.path.dirname(os.path.abspath(path))
        require(os.path.isdir(folder) and os.access(folder, os.W_OK), option, path, "is not in a writable directory")
        require(not os.path.isdir(path), option, path, "is a directory")
    require(args.msh is None or args.msh.endswith(".msh"), "--msh", args.msh, "must end in .msh")
    require(shutil.which("gmsh") is not None, "gmsh", "not found", "on PATH (Debian package gmsh)")
    return args


# --- Mesh: the same geometry, size field and algorithm as contactqp's half-disc mesher ----------

def fine_arc(args, max_gap):
    """The arc (angles phi, P(phi) = (R sin phi, R - R cos phi)) where contact can happen, sampled
    exactly as contactqp's fine_arc() for a plane obstacle y = 0 with normal (0, 1)."""
    R = args.radius
    start, end = (0.0 if args.symmetry else -math.pi / 2), math.pi / 2
    samples = 20000
    lo, hi = math.inf, -math.inf
    closest_phi, closest_gap = 0.0, math.inf
    for k in range(samples + 1):
        phi = start + (end - start) * k / samples
        gap = R - R * math.cos(phi)
        if -math.cos(phi) >= -1e-9:  # the outward normal does not face the obstacle
            continue
        if gap < closest_gap:
            closest_gap, closest_phi = gap, phi
        if gap <= max_gap:
            lo, hi = min(lo, phi), max(hi, phi)
    if lo > hi:
        return closest_phi, closest_phi
    widen = args.contact_size / R
    return max(start, lo - widen), min(end, hi + widen)


def estimated_triangles(args, fine):
    """contactqp's estimate_half_disc_triangles(): refuse oversized meshes before meshing."""
    R = args.radius
    cs, h, gamma = args.contact_size / R, args.size / R, args.grading
    area = math.pi / 4 if args.symmetry else math.pi / 2
    arc = max(0.0, fine[1] - fine[0])
    covered = triangles = 0.0
    d_max = max(0.0, (h - cs) / gamma)
    steps = 400
    for k in range(steps):
        if covered >= area:
            break
        d0, d1 = d_max * k / steps, d_max * (k + 1) / steps
        band = min((arc + math.pi * 0.5 * (d0 + d1)) * (d1 - d0), area - covered)
        local = cs + gamma * 0.5 * (d0 + d1)
        triangles += band / (TRIANGLE_AREA * local * local)
        covered += band
    return triangles + max(0.0, area - covered) / (TRIANGLE_AREA * h * h)


def geo_text(args, fine):
    """The .geo of contactqp's mesh_half_disc(), entity by entity in the same order."""
    R = args.radius
    phi_start, phi_end = (0.0 if args.symmetry else -math.pi / 2), math.pi / 2
    fine_from = min(max(fine[0], phi_start), phi_end)
    fine_to = min(max(fine[1], phi_start), phi_end)
    breaks = sorted([phi_start, phi_end, fine_from, fine_to] + ([] if args.symmetry else [0.0]))
    unique = [breaks[0]]
    for phi in breaks[1:]:
        if abs(phi - unique[-1]) >= 1e-9:
            unique.append(phi)
    breaks = unique

    g = lambda value: repr(float(value))
    lines = [f"// Hertz half disc for contactqp / GetFEM (R = {g(R)}; geometry in units of R, scaled on output)",
             "Point(1) = {0, 1, 0};"]
    for k, phi in enumerate(breaks):
        lines.append(f"Point({k + 2}) = {{{g(math.sin(phi))}, {g(1.0 - math.cos(phi))}, 0}};")
    arcs, fine_arcs = [], []
    for k in range(len(breaks) - 1):
        tag = k + 1
        lines.append(f"Circle({tag}) = {{{k + 2}, 1, {k + 3}}};")
        arcs.append(tag)
        middle = 0.5 * (breaks[k] + breaks[k + 1])
        if fine_from < middle < fine_to:
            fine_arcs.append(tag)
    last_point, first_point = len(breaks) + 1, 2
    top = len(arcs) + 1
    loop = list(arcs)
    if args.symmetry:
        symmetry = top + 1
        lines.append(f"Line({top}) = {{{last_point}, 1}};")
        lines.append(f"Line({symmetry}) = {{1, {first_point}}};")
        loop += [top, symmetry]
    else:
        lines.append(f"Line({top}) = {{{last_point}, {first_point}}};")
        loop.append(top)
    join = lambda tags: ", ".join(str(t) for t in tags)
    lines.append(f"Curve Loop(1) = {{{join(loop)}}};")
    lines.append("Plane Surface(1) = {1};")
    lines.append(f'Physical Curve("arc", {GROUPS["arc"][1]}) = {{{join(arcs)}}};')
    lines.append(f'Physical Curve("top", {GROUPS["top"][1]}) = {{{top}}};')
    if args.symmetry:
        lines.append(f'Physical Curve("symmetry", {GROUPS["symmetry"][1]}) = {{{symmetry}}};')
    lines.append(f'Physical Surface("body", {GROUPS["body"][1]}) = {{1}};')

    contact_size, size = args.contact_size / R, args.size / R
    lines.append("Field[1] = Distance;")
    if fine_arcs:
        points_per_curve = max(20.0, 4.0 * (fine_to - fine_from) / contact_size / len(fine_arcs))
        lines.append(f"Field[1].CurvesList = {{{join(fine_arcs)}}};")
        lines.append(f"Field[1].NumPointsPerCurve = {g(points_per_curve)};")
    else:  # no arc can touch: refine at the point closest to the obstacle
        closest = next((k for k, phi in enumerate(breaks) if phi >= fine_from - 1e-9), len(breaks) - 1)
        lines.append(f"Field[1].PointsList = {{{closest + 2}}};")
    lines.append("Field[2] = MathEval;")
    lines.append(f'Field[2].F = "Min({g(size)}, {g(contact_size)} + {g(args.grading)} * F1)";')
    lines.append("Background Field = 2;")
    lines += ["Mesh.MeshSizeExtendFromBoundary = 0;", "Mesh.MeshSizeFromPoints = 0;",
              "Mesh.MeshSizeFromCurvature = 0;", "Mesh.Algorithm = 6; // Frontal-Delaunay",
              f"Mesh.ElementOrder = {args.order};", f"Mesh.ScalingFactor = {g(R)};",
              "Mesh.MshFileVersion = 2.2;", "Mesh.Binary = 0;"]
    return "\n".join(lines) + "\n"


def gmsh_version():
    run = subprocess.run(["gmsh", "--version"], capture_output=True, text=True)
    return (run.stdout + run.stderr).strip().splitlines()[-1] if run.returncode == 0 else "unknown"


def make_mesh(args, fine, msh_path):
    geo_path = msh_path[:-4] + ".geo"
    with open(geo_path, "w") as stream:
        stream.write(geo_text(args, fine))
    run = subprocess.run(["gmsh", "-2", "-format", "msh22", geo_path, "-o", msh_path],
                         capture_output=True, text=True)
    if run.returncode != 0 or not os.path.exists(msh_path):
        raise ToolFailure("gmsh failed on " + geo_path + ": " + (run.stderr or run.stdout).strip()[-500:])
    return geo_path


def physical_groups(msh_path):
    """{name: (dimension, tag)} from the $PhysicalNames section."""
    with open(msh_path) as stream:
        text = stream.read()
    match = re.search(r"\$PhysicalNames\s*\n\s*\d+\s*\n(.*?)\$EndPhysicalNames", text, re.S)
    groups = {}
    for line in (match.group(1).strip().splitlines() if match else []):
        dim, tag, name = line.split(maxsplit=2)
        groups[name.strip('"')] = (int(dim), int(tag))
    return groups


# --- Solve -------------------------------------------------------------------------------------

def solve(gf, np, args, mesh, regions):
    E, nu, delta, R = args.E, args.nu, args.delta, args.radius
    max_gap = LOAD_GAP_FACTOR * delta
    ARC, TOP, SYM = regions["arc"], regions["top"], regions.get("symmetry")
    CONTACT = max(regions.values()) + 1
    # The contact boundary: the arc faces whose nodes are all candidates (gap <= max_gap).
    points = mesh.pts()
    arc_faces = mesh.region(ARC)
    keep = [j for j in range(arc_faces.shape[1])
            if np.all(points[1, mesh.pid_in_faces(arc_faces[:, j:j + 1])] <= max_gap)]
    if not keep:
        raise ToolFailure(f"no arc face lies within the candidate gap {max_gap:g} of the obstacle")
    mesh.set_region(CONTACT, arc_faces[:, keep])

    mfu = gf.MeshFem(mesh, 2)
    mfu.set_classical_fem(args.order)
    mfd = gf.MeshFem(mesh, 1)  # scalar data: the obstacle's signed distance, tributary lengths
    mfd.set_classical_fem(args.order)
    mim = gf.MeshIm(mesh, 2 * args.order)

    md = gf.Model("real")
    md.add_fem_variable("u", mfu)
    md.add_initialized_data("E", [E])
    md.add_initialized_data("nu", [nu])
    md.add_isotropic_linearized_elasticity_pstrain_brick(mim, "u", "E", "nu")
    md.add_initialized_data("top_displacement", [-delta])  # u.n on the cut, n = (0, 1)
    md.add_normal_Dirichlet_condition_with_multipliers(mim, "u", 1, TOP, "top_displacement")
    if SYM is not None:
        md.add_initialized_data("zero", [0.0])
        md.add_normal_Dirichlet_condition_with_multipliers(mim, "u", 1, SYM, "zero")
    else:
        md.add_initialized_data("pin_point", [0.0, R])
        md.add_initialized_data("pin_direction", [1.0, 0.0])
        md.add_pointwise_constraints_with_multipliers("u", "pin_point", "pin_direction")

    if args.formulation == "integral":
        mfl = gf.MeshFem(mesh, 1)
        mfl.set_classical_fem(args.order)
        md.add_filtered_fem_variable("lambda_n", mfl, CONTACT)
        md.add_initialized_fem_data("obstacle", mfd, mfd.eval("y"))
        md.add_initialized_data("r", [args.param * E])
        md.add_integral_contact_with_rigid_obstacle_brick(mim, "u", "lambda_n", "obstacle", "r", CONTACT, 1)
        parameters = {"r": args.param * E, "option": 1}
        multiplier = ("lambda_n", mfl, CONTACT)
    elif args.formulation == "nodal":
        multiplier = None
        md.add_variable("lambda_n", mfu.dof_on_region(CONTACT).size // 2)
        md.add_initialized_data("r", [args.param * E])
        md.add_nodal_contact_with_rigid_obstacle_brick(mim, "u", "lambda_n", "r", CONTACT, "y", 1)
        parameters = {"r": args.param * E, "augmented_version": 1}
    else:
        multiplier = None
        md.add_initialized_data("gamma0", [args.param / E])
        md.add_initialized_fem_data("obstacle", mfd, mfd.eval("y"))
        neumann = md.Neumann_term("u", CONTACT)
        md.add_Nitsche_contact_with_rigid_obstacle_brick(mim, "u", neumann, "obstacle", "gamma0", CONTACT, args.theta)
        parameters = {"gamma0": args.param / E, "theta": args.theta}
    clock = time.perf_counter()
    iterations, converged = md.solve("max_res", args.tol, "max_iter", args.max_iter)
    return {"seconds_newton": time.perf_counter() - clock, "model": md, "mfu": mfu, "mfd": mfd, "mim": mim,
            "iterations": int(iterations), "converged": bool(converged), "parameters": parameters,
            "max_gap": max_gap, "multiplier": multiplier}


# --- Post-processing, as contactqp's src/post/ ---------------------------------------------------

def contact_profile(gf, np, args, mesh, regions, solved):
    mfu, mfd, mim = solved["mfu"], solved["mfd"], solved["mim"]
    u = solved["model"].variable("u")
    E, nu = args.E, args.nu
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))  # plane strain Lame constants
    stress = f"({lam!r}*Trace(Grad_u)*Id(2) + {mu!r}*(Grad_u + Grad_u'))"
    reaction = gf.asm_generic(mim, 1, stress + ":Grad_Test_u", -1, "u", 1, mfu, u)  # K u
    tributary = gf.asm_generic(mim, 1, "Test_t", regions["arc"], "t", 1, mfd, np.zeros(mfd.nbdof()))

    arc_dofs = mfd.basic_dof_on_region(regions["arc"])
    nodes = mfd.basic_dof_nodes(arc_dofs)
    vector_nodes = mfu.basic_dof_nodes()
    profile = []
    # Penetration of the obstacle y = 0 by the deformed arc: allowed to be slightly positive
    # inside the contact zone by the weak formulations, and a sign of a too small candidate set
    # outside it (contactqp's penetrating_non_candidates).
    penetration = {"max_penetration": 0.0, "penetrating_non_candidates": 0}
    tolerance = 1e-6 * max(float(np.abs(u).max()), 1e-300)
    for dof, (x, y) in zip(arc_dofs, nodes.T):
        ydof = 2 * dof + 1  # classical vector FEM: DOFs interleaved (x, y) per scalar DOF
        assert np.allclose(vector_nodes[:, ydof], (x, y))
        depth = -(y + float(u[ydof]))
        if y > solved["max_gap"]:  # not a candidate: the obstacle is y = 0, normal (0, 1)
            penetration["penetrating_non_candidates"] += int(depth > tolerance)
            continue
        penetration["max_penetration"] = max(penetration["max_penetration"], depth)
        force = float(reaction[ydof])
        profile.append({"s": float(x), "force": force, "pressure": force / float(tributary[dof])})
    profile.sort(key=lambda point: point["s"])
    return profile, penetration


def multiplier_max_pressure(solved):
    """The integral formulation's contact stress field: its largest nodal value of -lambda_n (GetFEM's
    lambda_n is negative in compression). The nodal forces are its consistent boundary mass
    M (-lambda_n); the pressure F_i / w_i divides by the lumped mass instead (contactqp's definition)."""
    if solved["multiplier"] is None:
        return None
    name, mf, region = solved["multiplier"]
    values = solved["model"].variable(name)
    assert values.size == mf.basic_dof_on_region(region).size  # the filtered variable's DOFs
    return float(-values.min())


def summarize(args, profile):
    mirror = 2.0 if args.symmetry else 1.0
    total = sum(point["force"] for point in profile)
    centre = 0.0 if args.symmetry or not total > 0 else sum(p["force"] * p["s"] for p in profile) / total
    second = sum(p["force"] * (p["s"] - centre) ** 2 for p in profile)
    largest = max((p["force"] for p in profile), default=0.0)
    return {"total_force": mirror * total, "centre": centre,
            "half_width": 2.0 * math.sqrt(second / total) if total > 0 and second >= 0 else 0.0,
            "max_pressure": max((p["pressure"] for p in profile), default=0.0),
            "contact_nodes": sum(1 for p in profile if largest > 0 and p["force"] > 1e-8 * largest)}


def interpolated_pressure(profile, s):
    if not profile or s < profile[0]["s"] or s > profile[-1]["s"]:
        return 0.0
    for lower, upper in zip(profile, profile[1:]):
        if lower["s"] <= s <= upper["s"]:
            t = (s - lower["s"]) / (upper["s"] - lower["s"]) if upper["s"] > lower["s"] else 0.0
            return (1 - t) * lower["pressure"] + t * upper["pressure"]
    return profile[0]["pressure"]


def compare_with_hertz(args, profile, summary):
    P = summary["total_force"]
    if not P > 0:
        return None
    effective = args.E / (1 - args.nu ** 2)
    b = math.sqrt(4 * P * args.radius / (math.pi * effective))
    p0 = 2 * P / (math.pi * b)
    c = summary["centre"]
    hertz = lambda x: p0 * math.sqrt(1 - (x / b) ** 2) if abs(x) < b else 0.0
    breaks = sorted([max(0.0, c) if args.symmetry else c - b, c + b] + [p["s"] for p in profile])
    lo = 0.0 if args.symmetry else breaks[0]
    error = 0.0
    for a, z in zip(breaks, breaks[1:]):
        a = max(lo, a)
        if not z > a:
            continue
        for x, w in zip(GAUSS_X, GAUSS_W):
            s = 0.5 * (a + z) + 0.5 * (z - a) * x
            error += 0.5 * (z - a) * w * (interpolated_pressure(profile, s) - hertz(s - c)) ** 2
    reference = (2.0 / 3.0 if args.symmetry else 4.0 / 3.0) * p0 * p0 * b
    return {"effective_modulus": effective, "half_width": b, "max_pressure": p0,
            "error_half_width": (summary["half_width"] - b) / b,
            "error_max_pressure": (summary["max_pressure"] - p0) / p0,
            "error_l2": math.sqrt(error / reference)}


def write_json(path, data):
    folder = os.path.dirname(os.path.abspath(path))
    with tempfile.NamedTemporaryFile("w", dir=folder, delete=False, suffix=".tmp") as stream:
        json.dump(data, stream, indent=1)
        stream.write("\n")
    os.replace(stream.name, path)


def main(argv):
    try:
        args = parse_args(argv)
        max_gap = LOAD_GAP_FACTOR * args.delta
        fine = fine_arc(args, max_gap)
        estimate = estimated_triangles(args, fine)
        if estimate > args.max_elements:
            raise BadArgument(f"--size/--contact-size would give about {estimate:.0f} triangles, more than "
                              f"--max-elements = {args.max_elements}")
    except BadArgument as error:
        print(f"getfem_hertz: error: {error}", file=sys.stderr)
        return 2

    clock = time.perf_counter()
    import numpy as np
    import getfem as gf
    gf.util_trace_level(0)
    gf.util_warning_level(0)
    seconds_import = time.perf_counter() - clock

    scratch = tempfile.mkdtemp(prefix="getfem_hertz_")
    try:
        clock = time.perf_counter()
        msh_path = os.path.abspath(args.msh) if args.msh else os.path.join(scratch, "hertz.msh")
        geo_path = make_mesh(args, fine, msh_path)
        seconds_gmsh = time.perf_counter() - clock
        groups = physical_groups(msh_path)
        wanted = ["arc", "top", "body"] + (["symmetry"] if args.symmetry else [])
        missing = [name for name in wanted if groups.get(name) != GROUPS[name]]
        if missing:
            raise ToolFailure(f"{msh_path} lacks the physical groups {missing} (found {groups})")
        mesh = gf.Mesh("import", "gmsh", msh_path)
        regions = {name: GROUPS[name][1] for name in wanted if name != "body"}
        seconds_mesh = time.perf_counter() - clock

        all_seconds, newton_seconds = [], []
        for _ in range(args.repeat):  # each time from scratch: a new model, assembly and Newton solve
            clock = time.perf_counter()
            solved = solve(gf, np, args, mesh, regions)
            all_seconds.append(time.perf_counter() - clock)
            newton_seconds.append(solved["seconds_newton"])
        fastest = min(range(args.repeat), key=lambda k: all_seconds[k])
        seconds, seconds_newton = all_seconds[fastest], newton_seconds[fastest]

        clock = time.perf_counter()
        profile, penetration = contact_profile(gf, np, args, mesh, regions, solved)
        summary = summarize(args, profile)
        hertz = compare_with_hertz(args, profile, summary)
        mfu, md = solved["mfu"], solved["model"]
        prescribed = mfu.basic_dof_on_region(regions["top"]).size // 2
        if args.symmetry:
            prescribed += mfu.basic_dof_on_region(regions["symmetry"]).size // 2
        seconds_post = time.perf_counter() - clock
    except (ToolFailure, RuntimeError) as error:
        print(f"getfem_hertz: {error}", file=sys.stderr)
        return 1
    finally:
        shutil.rmtree(scratch, ignore_errors=True)

    result = {
        "converged": solved["converged"],
        "dofs": int(mfu.nbdof() - prescribed),
        "unknowns": int(md.nbdof()),
        "nodes": int(mesh.nbpts()),
        "elements": int(mesh.nbcvs()),
        "element_order": args.order,
        "newton_iterations": solved["iterations"],
        "seconds": seconds,
        "seconds_newton": seconds_newton,
        "seconds_all": all_seconds,
        "seconds_mesh": seconds_mesh,
        "seconds_gmsh": seconds_gmsh,
        "seconds_import": seconds_import,
        "seconds_post": seconds_post,
        "seconds_process": time.perf_counter() - START,
        "total_force": summary["total_force"],
        "half_width": summary["half_width"],
        "max_pressure": summary["max_pressure"],
        "multiplier_max_pressure": multiplier_max_pressure(solved),
        "contact_nodes": summary["contact_nodes"],
        "max_penetration": penetration["max_penetration"],
        "penetrating_non_candidates": penetration["penetrating_non_candidates"],
        "candidates": len(profile),
        "hertz": hertz,
        "formulation": args.formulation,
        "formulation_parameters": solved["parameters"],
        "newton": {"max_res": args.tol, "max_iter": args.max_iter, "linear_solver": "auto (MUMPS)"},
        "getfem_version": gf.getfem_env("release"),
        "gmsh_version": gmsh_version(),
        "mesh": {"msh": os.path.abspath(args.msh) if args.msh else None,
                 "geo": geo_path if args.msh else None, "radius": args.radius, "size": args.size,
                 "contact_size": args.contact_size, "grading": args.grading, "symmetry": args.symmetry,
                 "fine_arc": list(fine), "candidate_max_gap": max_gap},
        "problem": {"radius": args.radius, "E": args.E, "nu": args.nu, "delta": args.delta, "model": "plane_strain"},
        "profile": [[p["s"], p["pressure"], p["force"]] for p in profile],
        "profile_columns": ["s", "pressure", "force"],
    }
    write_json(args.out, result)
    h = hertz or {}
    print(f"getfem_hertz  {args.formulation}, order {args.order}: {result['dofs']} DOFs, {result['nodes']} nodes, "
          f"Newton {result['newton_iterations']} iterations ({'converged' if result['converged'] else 'NOT converged'}), "
          f"{seconds:.3f} s (mesh {seconds_mesh:.3f} s); P = {summary['total_force']:.7g}, "
          f"b error {100 * h.get('error_half_width', math.nan):+.2f}%, p0 error {100 * h.get('error_max_pressure', math.nan):+.2f}%, "
          f"L2 error {100 * h.get('error_l2', math.nan):.2f}%")
    return 0 if solved["converged"] else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
