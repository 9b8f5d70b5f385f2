"""contactqp.solve() and certify() on QPs with known solutions, with every available backend."""
import os
import subprocess
import sys

import numpy as np
import pytest
import scipy.sparse as sp

import contactqp
from conftest import random_qp, relative_difference, solve_by_enumeration


def test_version_and_backends():
    assert contactqp.__version__.count(".") == 2
    names = [b.label for b in contactqp.Backend.__members__.values()]
    assert names == ["uzawa", "uzawa_accel", "ipopt", "nlopt", "active_set", "petsc"]
    for b in contactqp.Backend.__members__.values():
        assert contactqp.backend_available(b) == (b in contactqp.available_backends())
        assert contactqp.backend_available(b.label) == contactqp.backend_available(b)
    assert contactqp.Backend.UZAWA in contactqp.available_backends()


def test_numpy_arrays_in_do_not_import_scipy():
    """K and B given as numpy arrays: the same QP as scipy matrices, and scipy (0.1-0.15 s of
    start-up) is not imported. In a fresh interpreter: this one has scipy already."""
    script = """
import sys, numpy, contactqp
qp = contactqp.QuadraticProgram(numpy.array([[2.0, -1.0], [-1.0, 2.0]]), numpy.array([1.0, 1.0]),
                                numpy.array([[1.0, 0.0]]), numpy.array([0.25]))
s = contactqp.solve(qp, backend="active_set", tol=1e-12)
print(s.u[0], s.u[1], s.lam[0], "scipy" in sys.modules)
"""
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         env=dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path)))
    assert run.returncode == 0, run.stderr
    u0, u1, lam, scipy_imported = run.stdout.split()
    # u0 = 0.25 (bound active), then 2 u1 = 1 + u0, and λ = 1 + u1 - 2 u0.
    assert float(u0) == pytest.approx(0.25, rel=1e-12) and float(u1) == pytest.approx(0.625, rel=1e-12)
    assert float(lam) == pytest.approx(1.125, rel=1e-12)
    assert scipy_imported == "False"


def test_hand_solved_qp(backend, hand_solved_qp):
    s = contactqp.solve(hand_solved_qp, backend=backend, tol=1e-10)
    assert s.status == contactqp.Status.CONVERGED, s.message
    assert s.converged and s.backend == backend
    np.testing.assert_allclose(s.u, [0.5, 0.75], rtol=1e-8)
    np.testing.assert_allclose(s.lam, [0.75], rtol=1e-8)
    assert s.x is not s.u and np.array_equal(s.x, s.u) and np.array_equal(s.z, s.lam)
    assert s.certificate.kkt_max < 1e-8
    assert s.certificate.objective == pytest.approx(hand_solved_qp.objective(s.u), rel=1e-14)
    assert "total" in s.timings and s.timings["total"] >= 0
    assert s.iterations >= 1


@pytest.mark.parametrize("seed", range(1, 7))
def test_random_qp_matches_enumeration(backend, seed):
    """The acceptance check: a random QP with a known solution, solved by every backend to 1e-8."""
    K, f, B, g = random_qp(8, 6, seed)
    u_exact, lam_exact = solve_by_enumeration(K, f, B, g)
    qp = contactqp.QuadraticProgram(sp.csr_matrix(K), f, sp.coo_matrix(B), g)
    s = contactqp.solve(qp, backend=backend, tol=1e-10, max_iterations=100000)
    assert s.status == contactqp.Status.CONVERGED, s.message
    assert relative_difference(s.u, u_exact) < 1e-8
    assert np.linalg.norm(s.lam - lam_exact) < 1e-8 * max(1.0, np.linalg.norm(lam_exact))
    c = s.certificate
    assert c.kkt_max < 1e-8 and abs(c.relative_gap) < 1e-8


def test_spring_against_wall(backend):
    """u = min(F/k, gap), lam = max(0, F - k gap): the wall pushes back."""
    k, F, gap = 4.0, 2.0, 0.1
    qp = contactqp.QuadraticProgram(np.array([[k]]), np.array([F]), np.array([[1.0]]), np.array([gap]))
    s = contactqp.solve(qp, backend=backend, tol=1e-12)
    assert s.converged, s.message
    assert s.u[0] == pytest.approx(gap, rel=1e-9)
    assert s.lam[0] == pytest.approx(F - k * gap, rel=1e-9)


def test_unconstrained_qp_is_the_linear_solution(backend):
    K = np.array([[2.0, 1.0], [1.0, 3.0]])
    f = np.array([1.0, 2.0])
    s = contactqp.solve(contactqp.QuadraticProgram(K, f), backend=backend, tol=1e-12)
    assert s.converged, s.message
    np.testing.assert_allclose(s.u, np.linalg.solve(K, f), rtol=1e-10)
    assert s.lam.shape == (0,)


@pytest.mark.parametrize("fmt", ["csc", "csr", "coo", "lil", "dok", "dense"])
def test_every_matrix_format_gives_the_same_qp(fmt):
    K, f, B, g = random_qp(6, 4, 3)
    convert = (lambda M: M) if fmt == "dense" else (lambda M: sp.csc_matrix(M).asformat(fmt))
    qp = contactqp.QuadraticProgram(convert(K), f, convert(B), g)
    np.testing.assert_array_equal(qp.K.toarray(), K)
    np.testing.assert_array_equal(qp.B.toarray(), B)
    assert (qp.n_dofs, qp.n_constraints) == (6, 4)


def test_duplicates_in_coo_are_summed_like_scipy():
    K = sp.coo_matrix(([1.0, 1.0, 3.0], ([0, 0, 1], [0, 0, 1])), shape=(2, 2))
    qp = contactqp.QuadraticProgram(K, np.zeros(2))
    np.testing.assert_array_equal(qp.K.toarray(), [[2.0, 0.0], [0.0, 3.0]])


def test_solve_leaves_the_inputs_untouched():
    K, f, B, g = random_qp(5, 4, 42)
    K_csc, f0, g0 = sp.csc_matrix(K), f.copy(), g.copy()
    qp = contactqp.QuadraticProgram(K_csc, f, B, g)
    contactqp.solve(qp, backend="uzawa", tol=1e-10)
    np.testing.assert_array_equal(K_csc.toarray(), K)
    np.testing.assert_array_equal(f, f0)
    np.testing.assert_array_equal(qp.g, g0)


def test_certify_judges_any_pair(hand_solved_qp):
    exact = contactqp.certify(hand_solved_qp, [0.5, 0.75], [0.75])
    assert exact.kkt_max < 1e-15 and abs(exact.relative_gap) < 1e-15
    # Infeasible u and a wrong multiplier: every residual says so.
    wrong = contactqp.certify(hand_solved_qp, np.array([0.6, 0.75]), np.array([0.0]))
    assert wrong.primal_feasibility > 0.1 and wrong.stationarity > 0.1
    # J(u) = u0^2 - u0 u1 + u1^2 - u0 - u1 at (0.5, 0.75): 0.25 - 0.375 + 0.5625 - 1.25.
    assert exact.objective == pytest.approx(-0.8125, rel=1e-15)
    d = exact.as_dict()
    assert d["objective"] == exact.objective and d["kkt_max"] == exact.kkt_max


def test_rho_and_backend_options_reach_the_backend(hand_solved_qp):
    s = contactqp.solve(hand_solved_qp, backend=contactqp.Backend.UZAWA, rho="0.5x", tol=1e-10)
    assert s.converged
    assert s.diagnostics["rho"] == pytest.approx(0.5 * s.diagnostics["rho_max"], rel=1e-12)
    s = contactqp.solve(hand_solved_qp, backend="uzawa", rho=0.1, tol=1e-10)
    assert s.diagnostics["rho"] == pytest.approx(0.1, rel=1e-12)
    if contactqp.backend_available("nlopt"):
        # The option reaches NLopt: its message names the algorithm that ran (L-BFGS by default).
        s = contactqp.solve(hand_solved_qp, backend="nlopt", backend_options={"algorithm": "LD_MMA"},
                            tol=1e-10, max_iterations=50)
        assert "LD_MMA" in s.message
        assert "LD_MMA" not in contactqp.solve(hand_solved_qp, backend="nlopt", tol=1e-10).message
    few = contactqp.solve(contactqp.QuadraticProgram(*random_qp(8, 6, 1)), backend="uzawa", rho="0.01x",
                          max_iterations=3, tol=1e-12)
    assert few.status == contactqp.Status.MAX_ITERATIONS and few.iterations == 3


def test_help_shows_a_call_example():
    doc = contactqp.solve.__doc__
    assert "contactqp.solve(qp, backend=" in doc and "P = K" in contactqp.__doc__
    for name in ["solve", "certify", "solve_scene", "compare_scene", "available_backends", "backend_available",
                 "QuadraticProgram", "Solution", "Certificate", "SceneResult", "Comparison", "InputError"]:
        assert getattr(contactqp, name).__doc__, name


def test_a_chain_held_only_by_its_wall_is_solved_on_its_free_mode():
    """A free chain of springs 1 and 2 pushed by 1 against a wall 0.5 right of its last mass:
    u = (2, 1, 0.5), lam = 1 by hand. With its null space given (or without: solve() finds it),
    active_set solves it on the chain's translation and reports that mode's balance."""
    K = sp.csr_matrix(np.array([[1.0, -1.0, 0.0], [-1.0, 3.0, -2.0], [0.0, -2.0, 2.0]]))
    f, B, g = np.array([1.0, 0.0, 0.0]), sp.csr_matrix([[0.0, 0.0, 1.0]]), np.array([0.5])
    held = contactqp.QuadraticProgram(K, f, B, g, null_space=np.ones(3))
    assert held.null_space.shape == (3, 1)
    assert contactqp.QuadraticProgram(K, f, B, g).null_space.shape == (3, 0)
    for qp in (held, contactqp.QuadraticProgram(K, f, B, g)):
        s = contactqp.solve(qp, backend="active_set", tol=1e-10)
        assert s.converged, s.message
        np.testing.assert_allclose(s.u, [2.0, 1.0, 0.5], rtol=1e-8)
        np.testing.assert_allclose(s.lam, [1.0], rtol=1e-8)
        assert s.null_space_dimension == 1
        assert s.diagnostics["rigid_balance"] <= 1e-9
    with pytest.raises(contactqp.InputError, match="null_space"):
        contactqp.QuadraticProgram(K, f, B, g, null_space=np.array([1.0, 0.0, 0.0]))
    with pytest.raises(contactqp.InputError, match="null_space"):
        contactqp.QuadraticProgram(K, f, B, g, null_space=np.ones(2))


def test_a_qp_without_solution_says_so_with_its_evidence(backend):
    """A floating chain pulled away from its only wall is unbounded; contradictory rows are
    infeasible: never CONVERGED, on every backend, with the evidence checked here."""
    K = sp.csr_matrix(np.array([[1.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]]))
    pulled = contactqp.QuadraticProgram(K, np.array([-1.0, 0.0, 0.0]), sp.csr_matrix([[0.0, 0.0, 1.0]]),
                                        np.array([0.5]))
    s = contactqp.solve(pulled, backend=backend)
    assert s.status == contactqp.Status.UNBOUNDED and not s.converged, s.message
    d = s.recession
    assert pulled.f @ d > 0 and (pulled.B @ d).max() <= 1e-12
    np.testing.assert_allclose(np.abs(d), np.full(3, 3 ** -0.5), rtol=1e-8)  # the chain's translation
    assert s.null_space_dimension == 1 and s.farkas is None
    assert np.all(s.u == 0) and np.all(s.lam == 0)

    grounded = sp.csr_matrix(np.array([[2.0, -1.0], [-1.0, 1.0]]))
    rows = sp.csr_matrix(np.array([[1.0, 0.0], [-1.0, 0.0]]))  # u0 <= -1 and u0 >= 1
    contradictory = contactqp.QuadraticProgram(grounded, np.array([0.3, 0.0]), rows, np.array([-1.0, -1.0]))
    s = contactqp.solve(contradictory, backend=backend)
    assert s.status == contactqp.Status.INFEASIBLE, s.message
    y = s.farkas
    assert y.min() >= 0 and contradictory.g @ y < 0 and np.abs(contradictory.B.T @ y).max() < 1e-12
    assert s.recession is None
