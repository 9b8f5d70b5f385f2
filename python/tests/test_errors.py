"""Bad input raises contactqp.InputError (a ValueError) naming the field, never a crash."""
import math

import numpy as np
import pytest
import scipy.sparse as sp

import contactqp
from conftest import source_path

K = np.array([[2.0, -1.0], [-1.0, 2.0]])
f = np.array([1.0, 1.0])
B = np.array([[1.0, 0.0]])
g = np.array([0.5])


def raises_naming(field, call, *args, **kwargs):
    with pytest.raises(contactqp.InputError) as info:
        call(*args, **kwargs)
    error = info.value
    assert isinstance(error, ValueError)
    assert error.field == field, str(error)
    assert str(error).startswith(field), str(error)
    assert "\n" not in str(error)
    return str(error)


@pytest.fixture
def qp():
    return contactqp.QuadraticProgram(K, f, B, g)


@pytest.mark.parametrize("field,args", [
    ("K", (np.ones((2, 3)), f, B, g)),                    # not square
    ("K", (np.ones(4), f, B, g)),                         # not 2-D
    ("K", ("stiffness", f, B, g)),                        # not numbers
    ("f", (K, np.ones(3), B, g)),                         # length differs from K
    ("f", (K, np.ones((2, 1)), B, g)),                    # a column, not a vector
    ("B", (K, f, np.ones((1, 3)), g)),                    # columns differ from K
    ("g", (K, f, B, np.ones(2))),                         # length differs from B's rows
    ("g", (K, f, B, None)),                               # B without g
    ("B", (K, f, None, g)),                               # g without B
])
def test_wrong_shapes(field, args):
    message = raises_naming(field, contactqp.QuadraticProgram, *args)
    assert "must" in message or "has" in message


@pytest.mark.parametrize("field", ["K", "f", "B", "g"])
@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_non_finite_entries(field, bad):
    data = {"K": K.copy(), "f": f.copy(), "B": B.copy(), "g": g.copy()}
    data[field].flat[0] = bad
    if field == "K":
        data["K"] = sp.csr_matrix(data["K"])  # sparse input is checked too
    message = raises_naming(field, contactqp.QuadraticProgram, data["K"], data["f"], data["B"], data["g"])
    assert "finite" in message


def test_K_not_symmetric():
    message = raises_naming("K", contactqp.QuadraticProgram, np.array([[2.0, -1.0], [-0.5, 2.0]]), f, B, g)
    assert "symmetric" in message
    # Round-off of an assembly passes.
    contactqp.QuadraticProgram(np.array([[2.0, -1.0], [-1.0 + 1e-15, 2.0]]), f, B, g)


def test_negative_or_out_of_range_tol(qp):
    assert "tol = -1" in raises_naming("tol", contactqp.solve, qp, tol=-1.0)
    raises_naming("tol", contactqp.solve, qp, tol=0.0)
    raises_naming("tol", contactqp.solve, qp, tol=2.0)
    raises_naming("tol", contactqp.solve, qp, tol="small")
    raises_naming("tol", contactqp.solve_scene, source_path("scenes/hertz.json"), tol=-1e-8)


def test_unknown_backend(qp):
    message = raises_naming("backend", contactqp.solve, qp, backend="ipot")
    assert "uzawa" in message and "active_set" in message  # the valid names
    raises_naming("backend", contactqp.solve, qp, backend=3.5)
    raises_naming("backend", contactqp.solve_scene, source_path("scenes/hertz.json"), backend="gurobi")
    raises_naming("backends", contactqp.compare_scene, source_path("scenes/hertz.json"), backends=["uzawa", "nope"])
    raises_naming("backends", contactqp.compare_scene, source_path("scenes/hertz.json"), backends=["uzawa", "uzawa"])


def test_non_callable_observer(qp):
    assert "callable" in raises_naming("observer", contactqp.solve, qp, observer=42)
    raises_naming("observer", contactqp.solve_scene, source_path("scenes/hertz.json"), observer="print")


def test_other_options(qp):
    raises_naming("max_iterations", contactqp.solve, qp, max_iterations=0)
    raises_naming("max_iterations", contactqp.solve, qp, max_iterations=1.5)
    raises_naming("max_iterations", contactqp.solve, qp, max_iterations=2 ** 80)
    raises_naming("max_elements", contactqp.solve_scene, source_path("scenes/hertz.json"), max_elements=0)
    raises_naming("max_elements", contactqp.solve_scene, source_path("scenes/hertz.json"), max_elements="many")
    # Within range but too small for the scene: the mesh refuses, naming its own field.
    assert "limit of 10" in raises_naming("body.mesh", contactqp.solve_scene, source_path("scenes/hertz.json"),
                                          max_elements=10)
    raises_naming("rho", contactqp.solve, qp, rho=-1.0)
    raises_naming("rho", contactqp.solve, qp, rho="fast")
    raises_naming("backend_options", contactqp.solve, qp, backend_options=["a=b"])
    raises_naming("backend_options.print_level", contactqp.solve, qp, backend="ipopt",
                  backend_options={"print_level": [5]})


def test_certify_arguments(qp):
    raises_naming("u", contactqp.certify, qp, [1.0, 2.0, 3.0], [0.0])
    raises_naming("lam", contactqp.certify, qp, [1.0, 2.0], [0.0, 1.0])
    raises_naming("u", contactqp.certify, qp, [math.nan, 2.0], [0.0])
    raises_naming("lam", contactqp.certify, qp, [1.0, 2.0], [math.inf])
    raises_naming("u", qp.objective, [1.0])


def test_scene_errors_name_the_path_or_key(tmp_path):
    raises_naming("path", contactqp.solve_scene, 17)
    missing = str(tmp_path / "missing.json")
    with pytest.raises(contactqp.InputError, match="missing.json"):
        contactqp.solve_scene(missing)
    bad = tmp_path / "bad.json"
    bad.write_text(open(source_path("scenes/hertz.json")).read().replace('"nu": 0.3', '"nu": 0.5'))
    with pytest.raises(contactqp.InputError) as info:
        contactqp.solve_scene(bad)
    assert info.value.field == "material.nu"
