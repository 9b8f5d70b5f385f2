"""The observer: every iterate reaches Python; weak duality J(u) >= theta(lam) on each feasible one."""
import numpy as np
import pytest

import contactqp
from conftest import random_qp, source_path


def dual_function(K, f, B, g, lam):
    """theta(lam) = -1/2 (f - B'lam)' K^-1 (f - B'lam) - g'lam, by numpy alone."""
    r = f - B.T @ lam
    return -0.5 * r @ np.linalg.solve(K, r) - g @ lam


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_weak_duality_on_every_feasible_iterate(backend, seed):
    K, f, B, g = random_qp(10, 8, seed)
    qp = contactqp.QuadraticProgram(K, f, B, g)
    iterates = []
    s = contactqp.solve(qp, backend=backend, tol=1e-10, max_iterations=100000,
                        observer=lambda k, u, lam: iterates.append((k, u.copy(), lam.copy())))
    assert s.converged, s.message
    assert iterates, "the observer was never called"
    ks = [k for k, _, _ in iterates]
    assert ks == sorted(ks) and ks[0] >= 1
    feasible = 0
    for k, u, lam in iterates:
        assert u.shape == (10,) and lam.shape == (8,)
        assert np.all(lam >= 0), f"iterate {k}: lam < 0"
        J = 0.5 * u @ K @ u - f @ u
        theta = dual_function(K, f, B, g, lam)
        slack = B @ u - g
        roundoff = 1e-12 * max(1.0, abs(J), abs(theta), abs(lam @ slack))
        # theta(lam) = min over u of the Lagrangian, so theta(lam) <= J(u) + lam'(Bu - g) for any u.
        assert J + lam @ slack >= theta - roundoff, f"iterate {k}"
        if np.all(slack <= 1e-12 * max(1.0, np.abs(g).max())):
            # A feasible u makes lam'(Bu - g) <= 0: weak duality itself.
            assert J >= theta - roundoff, f"iterate {k}"
            feasible += 1
    # The dual methods (Uzawa, NLopt on the dual) approach from outside the feasible set, so
    # their iterates are feasible only to round-off; the primal ones stay inside.
    if backend in (contactqp.Backend.IPOPT, contactqp.Backend.ACTIVE_SET):
        assert feasible >= 1


def test_observer_sees_the_callers_units():
    """Scaling is internal: the observer's last iterate is the returned solution's scale."""
    K, f, B, g = random_qp(6, 4, 5)
    scale = 1e6
    qp = contactqp.QuadraticProgram(scale * K, scale * f, B, g)
    last = {}
    s = contactqp.solve(qp, backend="uzawa", tol=1e-12, observer=lambda k, u, lam: last.update(u=u, lam=lam))
    np.testing.assert_allclose(last["u"], s.u, rtol=1e-6, atol=1e-9 * np.abs(s.u).max())
    np.testing.assert_allclose(last["lam"], s.lam, rtol=1e-6, atol=1e-9 * np.abs(s.lam).max())


def test_an_exception_in_the_observer_is_raised_after_the_solve():
    qp = contactqp.QuadraticProgram(*random_qp(6, 4, 5))
    calls = []

    def observer(k, u, lam):
        calls.append(k)
        raise RuntimeError("stop looking")

    with pytest.raises(RuntimeError, match="stop looking"):
        contactqp.solve(qp, backend="uzawa", tol=1e-12, observer=observer)
    assert calls == [1]  # called once, then no more


def test_solve_scene_observer():
    seen = []
    r = contactqp.solve_scene(source_path("scenes/hertz.json"), backend="uzawa", observer=lambda k, u, lam: seen.append(k))
    assert seen and seen[-1] <= r.iterations + 1 and len(r.lam) > 0
