#!/usr/bin/python3
"""Bring your own model: GetFEM assembles a contact problem, contactqp solves it.

An elastic block whose bottom is curved is pressed onto the rigid plane "height = 0" by a
prescribed displacement delta of its flat top, downwards:
  --dim 2 (default): plane strain, the block x in [-1, 1], y in [0, H], bottom y = c x^2;
  --dim 3: 3D elasticity, the block x, y in [-1, 1], z in [0, H], bottom z = c (x^2 + y^2)
           (a paraboloid: a circular contact patch, tetrahedra).
GetFEM (Debian's python3-getfem) builds the mesh and assembles the stiffness; this script turns
the model into contactqp's QP

    minimise  1/2 u^T K u - f^T u   subject to   B u <= g

over the free DOFs (the top's prescribed displacement moved into f = -K_fp u_p), with one row
per bottom node: -u_h <= h (h the node's height: its initial gap to the plane along the plane's
normal). contactqp solves it with every available backend and certifies each answer. The same
problem is then solved by GetFEM's own nodal contact brick
(add_nodal_contact_with_rigid_obstacle_brick, one multiplier per node, Alart-Curnier, Newton) on
the same mesh; the displacements must agree to 1e-6 relative (they agree to about the backends'
tolerance).

Run:  /usr/bin/python3 examples/getfem_contact.py [--dim 3] [--nx 40] [--tol 1e-10]
(with the module on PYTHONPATH, e.g. PYTHONPATH=build/python, or after `cmake --install`).
Exit status 0 when every backend converged and agrees with GetFEM, 1 otherwise.
"""
import argparse
import sys

import numpy as np
import scipy.sparse as sp

import contactqp

# The problem, in any consistent units.
E, NU = 1.0, 0.3         # Young's modulus, Poisson's ratio (plane strain in 2D)
WIDTH, HEIGHT = 2.0, 0.5  # the block spans [-1, 1] across (x, and y in 3D); its top is at HEIGHT
CURVATURE = 0.2          # bottom height = CURVATURE |x|^2: the gap at the side faces is 0.2
DELTA = 0.02             # downward displacement of the top: contact over |x| < about 0.3
AGREEMENT = 1e-6         # required ||u_contactqp - u_getfem|| / ||u_getfem||
BOTTOM, TOP = 1, 2       # GetFEM region numbers


def build_mesh(gf, dim, nx, ny):
    """A structured simplex mesh of the block (nx elements across, ny through the height), regions
    marked, then bent: h -> h + c |x|^2 (1 - h/H) keeps the top flat and makes the bottom the
    parabola (2D) or paraboloid (3D); the regions follow the faces."""
    across = np.linspace(-WIDTH / 2, WIDTH / 2, nx + 1)
    axes = [across] * (dim - 1) + [np.linspace(0, HEIGHT, ny + 1)]
    mesh = gf.Mesh("regular simplices", *axes)
    down = [0.0] * (dim - 1)
    mesh.set_region(BOTTOM, mesh.outer_faces_with_direction(down + [-1.0], 0.01))
    mesh.set_region(TOP, mesh.outer_faces_with_direction(down + [1.0], 0.01))
    points = mesh.pts()
    horizontal, height = points[:-1], points[-1]
    bent = height + CURVATURE * (horizontal ** 2).sum(axis=0) * (1 - height / HEIGHT)
    mesh.set_pts(np.vstack([horizontal, bent]))
    return mesh


def elasticity_model(gf, mesh):
    dim = mesh.dim()
    mfu = gf.MeshFem(mesh, dim)
    mfu.set_classical_fem(1)
    mim = gf.MeshIm(mesh, 2)
    model = gf.Model("real")
    model.add_fem_variable("u", mfu)
    if dim == 2:
        model.add_initialized_data("E", [E])
        model.add_initialized_data("nu", [NU])
        model.add_isotropic_linearized_elasticity_pstrain_brick(mim, "u", "E", "nu")
    else:  # 3D: GetFEM's brick takes the Lamé coefficients
        model.add_initialized_data("lambda", [E * NU / ((1 + NU) * (1 - 2 * NU))])
        model.add_initialized_data("mu", [E / (2 * (1 + NU))])
        model.add_isotropic_linearized_elasticity_brick(mim, "u", "lambda", "mu")
    return model, mfu, mim


def to_scipy(spmat):
    """GetFEM's Spmat as scipy.sparse.csc_matrix."""
    jc, ir = spmat.csc_ind()
    n_rows, n_cols = spmat.size()
    return sp.csc_matrix((spmat.csc_val(), ir, jc), shape=(n_rows, n_cols))


def assemble_contact_qp(gf, mesh):
    """contactqp's QP from GetFEM's stiffness: returns the QP and what is needed to rebuild the full u."""
    dim = mesh.dim()
    model, mfu, _ = elasticity_model(gf, mesh)
    model.assembly("build_matrix")
    K_full = to_scipy(model.tangent_matrix()).tocsr()
    n = mfu.nbdof()
    # Classical vector P1: DOFs interleaved (x, y[, z]) per node; the last one is the height.
    vertical = dim - 1
    prescribed = np.unique(mfu.basic_dof_on_region(TOP))
    u_prescribed = np.zeros(n)
    u_prescribed[prescribed[prescribed % dim == vertical]] = -DELTA
    free = np.setdiff1d(np.arange(n), prescribed)
    column = -np.ones(n, dtype=int)
    column[free] = np.arange(free.size)
    K = K_full[free][:, free]
    f = -(K_full[free][:, prescribed] @ u_prescribed[prescribed])
    # One contact row per bottom node (its vertical DOF): -u_h <= h, the gap along the plane's normal.
    bottom = np.unique(mfu.basic_dof_on_region(BOTTOM))
    bottom = bottom[(bottom % dim == vertical) & (column[bottom] >= 0)]
    gaps = mfu.basic_dof_nodes(bottom)[vertical]
    rows = np.arange(bottom.size)
    B = sp.csr_matrix((-np.ones(bottom.size), (rows, column[bottom])), shape=(bottom.size, free.size))
    qp = contactqp.QuadraticProgram(K, f, B, gaps)
    return qp, free, u_prescribed


def getfem_reference(gf, mesh, tol):
    """The same problem by GetFEM alone: nodal contact with the rigid obstacle "height = 0" (signed
    distance "y" in 2D, "z" in 3D), Dirichlet condition on the top with multipliers, Newton on
    Alart-Curnier."""
    dim = mesh.dim()
    model, mfu, mim = elasticity_model(gf, mesh)
    model.add_initialized_data("top_displacement", [0.0] * (dim - 1) + [-DELTA])
    model.add_Dirichlet_condition_with_multipliers(mim, "u", mfu, TOP, "top_displacement")
    model.add_variable("lambda_n", np.unique(mfu.basic_dof_on_region(BOTTOM)).size // dim)
    model.add_initialized_data("r", [E])
    model.add_nodal_contact_with_rigid_obstacle_brick(mim, "u", "lambda_n", "r", BOTTOM, "y" if dim == 2 else "z", 1)
    iterations, converged = model.solve("max_res", tol, "max_iter", 100)
    return model.variable("u"), int(iterations), bool(converged)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--dim", type=int, choices=(2, 3), default=2, help="2: plane strain (default), 3: solid")
    parser.add_argument("--nx", type=int, help="elements across the width (default 40 in 2D, 16 in 3D)")
    parser.add_argument("--ny", type=int, help="elements across the height (default 10 in 2D, 4 in 3D)")
    parser.add_argument("--tol", type=float, default=1e-10, help="contactqp's tolerance (default 1e-10)")
    args = parser.parse_args(argv)

    import getfem as gf
    gf.util_trace_level(0)
    gf.util_warning_level(0)
    nx = args.nx or (40 if args.dim == 2 else 16)
    ny = args.ny or (10 if args.dim == 2 else 4)
    mesh = build_mesh(gf, args.dim, nx, ny)
    qp, free, u_prescribed = assemble_contact_qp(gf, mesh)
    u_getfem, newton_iterations, newton_converged = getfem_reference(gf, mesh, 1e-12)
    print(f"GetFEM {gf.getfem_env('release')}, {args.dim}D: {mesh.nbpts()} nodes, QP with {qp.n_dofs} DOFs and "
          f"{qp.n_constraints} contact rows; nodal contact brick: Newton {newton_iterations} iterations"
          f"{'' if newton_converged else ' (NOT converged)'}")

    ok = newton_converged
    print(f"{'backend':<12} {'status':<15} {'iter':>6} {'KKT max':>9} {'rel gap':>10} {'|du|/|u| vs GetFEM':>19} {'force':>12} {'in contact':>10}")
    for backend in contactqp.available_backends():
        s = contactqp.solve(qp, backend=backend, tol=args.tol, max_iterations=100000)
        u = u_prescribed.copy()
        u[free] = s.u
        difference = np.linalg.norm(u - u_getfem) / np.linalg.norm(u_getfem)
        gap = s.certificate.relative_gap
        print(f"{backend.label:<12} {s.status.label:<15} {s.iterations:>6} {s.certificate.kkt_max:>9.2e} "
              f"{gap if gap is not None else float('nan'):>10.2e} {difference:>19.2e} {s.lam.sum():>12.6g} {int((s.lam > 1e-8 * s.lam.max()).sum()):>10}")
        ok = ok and s.converged and difference <= AGREEMENT
    print("agree with GetFEM within %g: %s" % (AGREEMENT, "yes" if ok else "NO"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
