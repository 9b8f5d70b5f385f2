"""The battery of bad input, Python's share (the command line's is tests/input/test_battery.cpp):
every call raises contactqp.InputError (a ValueError) whose one-line message starts with the
field it names — never another exception, a crash or a result."""
import math
import pathlib

import numpy as np
import pytest

import contactqp
from conftest import source_path

HERTZ = source_path("scenes/hertz.json")
K = np.array([[2.0, -1.0], [-1.0, 2.0]])
f = np.array([1.0, 1.0])
B = np.array([[1.0, 0.0]])
g = np.array([0.5])


def check(field, call, *args, **kwargs):
    with pytest.raises(contactqp.InputError) as info:
        call(*args, **kwargs)
    message = str(info.value)
    assert info.value.field == field, message
    assert message.startswith(field), message
    assert "\n" not in message
    return message


SOLVE_SCENE_ARGUMENTS = [
    ("tol", {"tol": math.nan}),
    ("tol", {"tol": math.inf}),
    ("tol", {"tol": -0.0}),
    ("tol", {"tol": True}),
    ("tol", {"tol": "1e-8"}),
    ("tol", {"tol": [1e-8]}),
    ("rho", {"rho": math.nan}),
    ("rho", {"rho": -math.inf}),
    ("rho", {"rho": 0}),
    ("rho", {"rho": "0.5y"}),
    ("rho", {"rho": [0.5]}),
    ("max_iterations", {"max_iterations": -1}),
    ("max_iterations", {"max_iterations": 0}),
    ("max_iterations", {"max_iterations": 1e3}),
    ("max_iterations", {"max_iterations": 2 ** 31}),
    ("max_iterations", {"max_iterations": True}),
    ("max_elements", {"max_elements": -5}),
    ("max_elements", {"max_elements": 2 ** 70}),
    ("max_elements", {"max_elements": 1.5}),
    ("backend", {"backend": "Uzawa"}),
    ("backend", {"backend": ""}),
    ("backend", {"backend": ["uzawa"]}),
    ("backend", {"backend": 0}),
    ("backend_options", {"backend_options": "print_level=5"}),
    ("backend option 1", {"backend_options": {1: 2}}),  # uzawa takes none
    ("backend_options.print_level", {"backend": "ipopt", "backend_options": {"print_level": None}}),
    ("observer", {"observer": 3}),
]


@pytest.mark.parametrize("field,arguments", SOLVE_SCENE_ARGUMENTS, ids=[repr(a) for _, a in SOLVE_SCENE_ARGUMENTS])
def test_solve_scene_arguments(field, arguments):
    if arguments.get("backend") == "ipopt" and contactqp.Backend.IPOPT not in contactqp.available_backends():
        pytest.skip("Ipopt not built in")
    check(field, contactqp.solve_scene, HERTZ, **arguments)


COMPARE_ARGUMENTS = [
    ("backends", {"backends": []}),
    ("backends", {"backends": ["uzawa", "uzawa"]}),
    ("backends", {"backends": ["nope"]}),
    ("backends", {"backends": [1]}),
    ("backends", {"backends": 5}),
    ("tol", {"tol": 2.0}),
    ("max_iterations", {"max_iterations": -3}),
]


@pytest.mark.parametrize("field,arguments", COMPARE_ARGUMENTS, ids=[repr(a) for _, a in COMPARE_ARGUMENTS])
def test_compare_scene_arguments(field, arguments):
    check(field, contactqp.compare_scene, HERTZ, **arguments)


BAD_SCENES = [  # (the field, text replaced in scenes/hertz.json, its replacement)
    ("material.poisson", '"nu": 0.3', '"poisson": 0.3'),
    ("material.nu", '"nu": 0.3', '"nu": 0.5'),
    ("material.nu", '"nu": 0.3', '"nu": "0.3"'),
    ("material.E", '"E": 1.0', '"E": -1'),
    ("material.E", '"E": 1.0', '"E": 1e308'),
    ("material.E", '"E": 1.0, "nu": 0.3', '"E": 1.0, "E": 2.0, "nu": 0.3'),
    ("body.radius", '"radius": 1.0', '"radius": 0'),
    ("body.mesh.sise", '"size"', '"sise"'),
    ("load.value", '[null, -0.016]', '[null, null]'),
    ("obstacle.normal", '"normal": [0.0, 1.0]', '"normal": [0, 0]'),
    ("model", '"plane_strain"', '"plane strain"'),
]


@pytest.mark.parametrize("field,old,new", BAD_SCENES, ids=[b[0] + ":" + b[2] for b in BAD_SCENES])
def test_bad_scenes(tmp_path, field, old, new):
    text = pathlib.Path(HERTZ).read_text()
    assert old in text
    path = tmp_path / "bad.json"
    path.write_text(text.replace(old, new, 1))
    check(field, contactqp.solve_scene, path)
    check(field, contactqp.compare_scene, path)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.json"]  # nothing written


def test_bad_files(tmp_path):
    assert "missing.json" in str(check(str(tmp_path / "missing.json"), contactqp.solve_scene,
                                       tmp_path / "missing.json"))
    check(str(tmp_path), contactqp.solve_scene, tmp_path)
    (tmp_path / "empty.json").write_text("")
    check(str(tmp_path / "empty.json"), contactqp.solve_scene, tmp_path / "empty.json")
    check("path", contactqp.solve_scene, None)
    check("path", contactqp.solve_scene, 3.5)
    # A .msh that is a script in disguise is refused before Gmsh would run it.
    script = tmp_path / "body.msh"
    script.write_text('SystemCall "touch %s";\n' % (tmp_path / "owned"))
    scene = tmp_path / "scene.json"
    scene.write_text(pathlib.Path(source_path("scenes/hertz-gmsh.json")).read_text().replace(
        "hertz_disc.geo", str(script)))
    assert "is not a Gmsh mesh file" in check(str(script), contactqp.solve_scene, scene)
    assert not (tmp_path / "owned").exists()


QP_ARGUMENTS = [
    ("K", (np.zeros((0, 0)), np.zeros(0), None, None)),
    ("K", (np.array([[math.nan]]), np.ones(1), None, None)),
    ("K", (np.array([[1.0, 2.0], [3.0, 4.0]]), f, B, g)),
    ("f", (K, np.array([1.0, math.inf]), B, g)),
    ("f", (K, "ones", B, g)),
    ("B", (K, f, np.array([[math.nan, 0.0]]), g)),
    ("B", (K, f, np.ones((1, 3)), g)),
    ("g", (K, f, B, np.array([math.nan]))),
    ("g", (K, f, B, np.array([]))),
]


@pytest.mark.parametrize("field,args", QP_ARGUMENTS, ids=[str(i) for i in range(len(QP_ARGUMENTS))])
def test_quadratic_program_arguments(field, args):
    check(field, contactqp.QuadraticProgram, *args)


def test_solve_and_certify_arguments():
    qp = contactqp.QuadraticProgram(K, f, B, g)
    check("tol", contactqp.solve, qp, tol=math.nan)
    check("rho", contactqp.solve, qp, rho=math.nan)
    check("backend", contactqp.solve, qp, backend="petsc_nope")
    check("u", contactqp.certify, qp, np.ones(3), np.zeros(1))
    check("lam", contactqp.certify, qp, np.ones(2), np.array([-math.inf]))
    check("u", contactqp.certify, qp, "u", np.zeros(1))
