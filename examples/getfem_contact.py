#!/usr/bin/python3
"""Bring your own model: GetFEM assembles a contact problem, contactqp solves it.

A 2D plane-strain elastic block whose bottom is the parabola y = c x^2 is pressed onto the rigid
plane y = 0 by a prescribed displacement (0, -delta) of its flat top y = H. GetFEM (Debian's
python3-getfem) builds the mesh and assembles the stiffness; this script turns the model into
contactqp's QP

    minimise  1/2 u^T K u - f^T u   subject to   B u <= g

over the free DOFs (the top's prescribed displacement moved into f = -K_fp u_p), with one row
per bottom node: -u_y <= y (the initial gap to the plane along its normal (0, 1)). contactqp
solves it with every available backend and certifies each answer. The same problem is then
solved by GetFEM's own nodal contact brick (add_nodal_contact_with_rigid_obstacle_brick, one
multiplier per node, Alart-Curnier, Newton) on the same mesh; the displacements must agree to
1e-6 relative (they agree to about the backends' tolerance).

Run:  /usr/bin/python3 examples/getfem_contact.py [--nx 40] [--tol 1e-10]
(with the module on PYTHONPATH, e.g. PYTHONPATH=build/python, or after `cmake --install`).
Exit status 0 when every backend converged and agrees with GetFEM, 1 otherwise.
"""
import argparse
import sys

import numpy as np
import scipy.sparse as sp

import contactqp

# The problem, in any consistent units.
E, NU = 1.0, 0.3         # Young's modulus, Poisson's ratio (plane strain)
WIDTH, HEIGHT = 2.0, 0.5  # the block spans x in [-1, 1]; its top is y = HEIGHT
CURVATURE = 0.2          # bottom y = CURVATURE x^2: the gap at x = +-1 is 0.2
DELTA = 0.02             # downward displacement of the top: contact over |x| < about 0.3
AGREEMENT = 1e-6         # required ||u_contactqp - u_getfem|| / ||u_getfem||
BOTTOM, TOP = 1, 2       # GetFEM region numbers


def build_mesh(gf, nx, ny):
    """A structured triangle mesh of the rectangle, regions marked, then bent: y -> y + c x^2 (1 - y/H)
    keeps the top flat and makes the bottom the parabola (the regions follow the faces)."""
    mesh = gf.Mesh("regular simplices", np.linspace(-WIDTH / 2, WIDTH / 2, nx + 1), np.linspace(0, HEIGHT, ny + 1))
    mesh.set_region(BOTTOM, mesh.outer_faces_with_direction([0.0, -1.0], 0.01))
    mesh.set_region(TOP, mesh.outer_faces_with_direction([0.0, 1.0], 0.01))
    points = mesh.pts()
    x, y = points[0], points[1]
    mesh.set_pts(np.vstack([x, y + CURVATURE * x ** 2 * (1 - y / HEIGHT)]))
    return mesh


def elasticity_model(gf, mesh):
    mfu = gf.MeshFem(mesh, 2)
    mfu.set_classical_fem(1)
    mim = gf.MeshIm(mesh, 2)
    model = gf.Model("real")
    model.add_fem_variable("u", mfu)
    model.add_initialized_data("E", [E])
    model.add_initialized_data("nu", [NU])
    model.add_isotropic_linearized_elasticity_pstrain_brick(mim, "u", "E", "nu")
    return model, mfu, mim


def to_scipy(spmat):
    """GetFEM's Spmat as scipy.sparse.csc_matrix."""
    jc, ir = spmat.csc_ind()
    n_rows, n_cols = spmat.size()
    return sp.csc_matrix((spmat.csc_val(), ir, jc), shape=(n_rows, n_cols))


def assemble_contact_qp(gf, mesh):
    """contactqp's QP from GetFEM's stiffness: returns the QP and what is needed to rebuild the full u."""
    model, mfu, _ = elasticity_model(gf, mesh)
    model.assembly("build_matrix")
    K_full = to_scipy(model.tangent_matrix()).tocsr()
    n = mfu.nbdof()
    # Classical vector P1: DOFs interleaved (x, y) per node.
    prescribed = np.unique(mfu.basic_dof_on_region(TOP))
    u_prescribed = np.zeros(n)
    u_prescribed[prescribed[prescribed % 2 == 1]] = -DELTA
    free = np.setdiff1d(np.arange(n), prescribed)
    column = -np.ones(n, dtype=int)
    column[free] = np.arange(free.size)
    K = K_full[free][:, free]
    f = -(K_full[free][:, prescribed] @ u_prescribed[prescribed])
    # One contact row per bottom node (its y DOF): -u_y <= y, the gap along the plane's normal.
    bottom_y = np.unique(mfu.basic_dof_on_region(BOTTOM))
    bottom_y = bottom_y[(bottom_y % 2 == 1) & (column[bottom_y] >= 0)]
    gaps = mfu.basic_dof_nodes(bottom_y)[1]
    rows = np.arange(bottom_y.size)
    B = sp.csr_matrix((-np.ones(bottom_y.size), (rows, column[bottom_y])), shape=(bottom_y.size, free.size))
    qp = contactqp.QuadraticProgram(K, f, B, gaps)
    return qp, free, u_prescribed


def getfem_reference(gf, mesh, tol):
    """The same problem by GetFEM alone: nodal contact with the rigid obstacle y = 0 (signed
    distance "y"), Dirichlet condition on the top with multipliers, Newton on Alart-Curnier."""
    model, mfu, mim = elasticity_model(gf, mesh)
    model.add_initialized_data("top_displacement", [0.0, -DELTA])
    model.add_Dirichlet_condition_with_multipliers(mim, "u", mfu, TOP, "top_displacement")
    model.add_variable("lambda_n", np.unique(mfu.basic_dof_on_region(BOTTOM)).size // 2)
    model.add_initialized_data("r", [E])
    model.add_nodal_contact_with_rigid_obstacle_brick(mim, "u", "lambda_n", "r", BOTTOM, "y", 1)
    iterations, converged = model.solve("max_res", tol, "max_iter", 100)
    return model.variable("u"), int(iterations), bool(converged)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--nx", type=int, default=40, help="elements across the width (default 40)")
    parser.add_argument("--ny", type=int, default=10, help="elements across the height (default 10)")
    parser.add_argument("--tol", type=float, default=1e-10, help="contactqp's tolerance (default 1e-10)")
    args = parser.parse_args(argv)

    import getfem as gf
    gf.util_trace_level(0)
    gf.util_warning_level(0)
    mesh = build_mesh(gf, args.nx, args.ny)
    qp, free, u_prescribed = assemble_contact_qp(gf, mesh)
    u_getfem, newton_iterations, newton_converged = getfem_reference(gf, mesh, 1e-12)
    print(f"GetFEM {gf.getfem_env('release')}: {mesh.nbpts()} nodes, QP with {qp.n_dofs} DOFs and "
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
