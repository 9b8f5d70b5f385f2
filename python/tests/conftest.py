"""Shared helpers for the contactqp pytest suite (run by ctest: python/CMakeLists.txt).

Reference solutions are computed here, independently of contactqp: small QPs are solved by
enumerating every active set with numpy, as the C++ suite's solve_by_enumeration does.
"""
import itertools
import json
import os
import subprocess

import numpy as np
import pytest
import scipy.sparse as sp

import contactqp

SOURCE_DIR = os.environ.get("CONTACTQP_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def source_path(relative):
    return os.path.join(SOURCE_DIR, relative)


CLI = os.environ.get("CONTACTQP_CLI", "contactqp")

# Wall times differ from run to run; everything else must agree to round-off.
TIMING_KEYS = {"timings", "seconds", "seconds_in_linear_solves", "factorize_seconds", "linear_solve_seconds"}


def cli_json(tmp_path, *arguments):
    """The command line's result JSON for these arguments (written under tmp_path), and the run."""
    out = tmp_path / "cli.json"
    run = subprocess.run([CLI, *arguments, "--json", str(out)], capture_output=True, text=True)
    assert run.returncode in (0, 1), run.stderr
    return json.loads(out.read_text()), run


def assert_same_numbers(a, b, path=""):
    """Every leaf equal, numbers to round-off (1e-12 relative), timings skipped."""
    if isinstance(a, dict):
        assert set(a) == set(b), path
        for key in a:
            if key not in TIMING_KEYS and not key.endswith("_seconds"):
                assert_same_numbers(a[key], b[key], path + "." + key)
    elif isinstance(a, list):
        assert len(a) == len(b), path
        for i, (x, y) in enumerate(zip(a, b)):
            assert_same_numbers(x, y, f"{path}[{i}]")
    elif isinstance(a, float) or isinstance(b, float):
        assert a == pytest.approx(b, rel=1e-12, abs=1e-300), path
    else:
        assert a == b, path


def solve_by_enumeration(K, f, B, g):
    """The exact solution of min 1/2 u'Ku - f'u s.t. Bu <= g (m <= 12): for each active set A,
    solve the equality-constrained KKT system and keep the primal and dual feasible one."""
    K, B = np.asarray(K, float), np.asarray(B, float)
    n, m = K.shape[0], B.shape[0]
    for size in range(m + 1):
        for active in itertools.combinations(range(m), size):
            a = list(active)
            Ba = B[a, :]
            kkt = np.block([[K, Ba.T], [Ba, np.zeros((size, size))]])
            rhs = np.concatenate([f, g[a]])
            try:
                x = np.linalg.solve(kkt, rhs)
            except np.linalg.LinAlgError:
                continue
            u, lam_a = x[:n], x[n:]
            if np.all(B @ u <= g + 1e-12) and np.all(lam_a >= -1e-12):
                lam = np.zeros(m)
                lam[a] = lam_a
                return u, lam
    raise AssertionError("no active set is feasible")


def random_qp(n, m, seed):
    """A random strictly convex QP whose solution has some rows active and some not."""
    rng = np.random.default_rng(seed)
    A = rng.standard_normal((n, n))
    K = A @ A.T + 0.5 * n * np.eye(n)
    f = rng.standard_normal(n)
    B = rng.standard_normal((m, n))
    B /= np.linalg.norm(B, axis=1, keepdims=True)
    g = B @ np.linalg.solve(K, f)
    g += np.where(np.arange(m) % 2 == 0, -0.5, 0.5) * np.abs(rng.standard_normal(m))
    return K, f, B, g


def relative_difference(a, b):
    return np.linalg.norm(a - b) / max(np.linalg.norm(b), 1e-300)


@pytest.fixture(params=contactqp.available_backends(), ids=lambda b: b.label)
def backend(request):
    """Every backend built into this copy (Ipopt and NLopt are optional at configure time)."""
    return request.param


@pytest.fixture
def hand_solved_qp():
    """min u0^2 - u0 u1 + u1^2 - u0 - u1  s.t.  u0 <= 0.5: the free optimum (1, 1) violates the
    row; on it, 2 u1 - 0.5 = 1 gives u1 = 0.75, and stationarity of row 0, 1 - 0.75 - 1 + lam = 0,
    gives lam = 0.75."""
    K = sp.csc_matrix([[2.0, -1.0], [-1.0, 2.0]])
    return contactqp.QuadraticProgram(K, np.array([1.0, 1.0]), np.array([[1.0, 0.0]]), np.array([0.5]))
