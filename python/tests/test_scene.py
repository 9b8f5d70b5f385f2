"""solve_scene() and compare_scene() give the numbers of the command line's JSON."""
import json
import subprocess
import threading

import numpy as np
import pytest

import contactqp
from conftest import CLI, assert_same_numbers, cli_json, source_path

HERTZ = source_path("scenes/hertz.json")


def test_hertz_force_b_p0_identical_to_the_cli(tmp_path, backend):
    """The acceptance check: the Hertz scene's force, b and p0 from Python equal the CLI's JSON."""
    expected, _ = cli_json(tmp_path, "solve", HERTZ, "--backend", backend.label, "--tol", "1e-10")
    r = contactqp.solve_scene(HERTZ, backend=backend, tol=1e-10)
    # On one process the CLI's petsc run is the distributed run on one part, while solve_scene()
    # keeps the one-process path, whose report holds u, the model and the QP whole
    # (docs/architecture.md, "Which path a scene takes"): two solvers of the same QP, so the same
    # answer to their tolerance (1e-11 on this scene), not to round-off, and files that differ
    # in the solver's diagnostics. Every other backend runs the same code in both.
    same_code = backend.label != "petsc"
    rel = 1e-12 if same_code else 1e-9
    assert r.status.label == expected["status"] == "converged"
    assert r.backend == backend and (r.iterations == expected["iterations"] or not same_code)
    assert r.contact.total_force == pytest.approx(expected["contact"]["total_force"], rel=rel)
    assert r.hertz.half_width == pytest.approx(expected["hertz"]["half_width"], rel=rel)
    assert r.hertz.max_pressure == pytest.approx(expected["hertz"]["max_pressure"], rel=rel)
    assert r.contact.half_width == pytest.approx(expected["contact"]["half_width"], rel=rel)
    assert r.contact.max_pressure == pytest.approx(expected["contact"]["max_pressure"], rel=rel)
    assert r.certificate.objective == pytest.approx(expected["objective"], rel=rel)
    assert (r.dofs, r.constraints, r.nodes) == (expected["dofs"], expected["constraints"], expected["nodes"])
    # And every other number of the file, through the report's own json().
    if same_code:
        assert_same_numbers(json.loads(r.json()), expected)


def test_attributes_are_numpy_and_consistent():
    r = contactqp.solve_scene(HERTZ, backend="active_set")
    assert isinstance(r.u, np.ndarray) and r.u.shape == (r.dofs,)
    assert isinstance(r.lam, np.ndarray) and r.lam.shape == (r.constraints,)
    assert np.all(r.lam >= 0)
    # The total force is the sum of the nodal forces, doubled by the symmetry plane.
    assert r.contact.total_force == pytest.approx(2 * r.lam.sum(), rel=1e-12)
    assert r.displacement.shape == (2 * r.nodes,)
    assert r.contact.profile.shape == (r.constraints, 2)
    assert list(r.timings)[-1] == "total" and r.timings["total"] >= r.timings["mesh"]
    assert r.reactions[0]["boundary"] == "top"
    # The reaction on the displaced top balances the contact force.
    assert -r.reactions[0]["force"][1] == pytest.approx(r.contact.total_force, rel=1e-8)
    # The QP behind it, solved again from Python, gives the same answer.
    again = contactqp.solve(r.qp, backend="active_set", tol=r.tol)
    np.testing.assert_allclose(again.u, r.u, rtol=0, atol=1e-14 * np.abs(r.u).max())


def test_a_force_on_a_rigid_surface_reports_how_far_the_surface_moved():
    # scenes/hertz-force.json: the force hertz.json's push of 0.016 gives, so the cut moves by it.
    r = contactqp.solve_scene(source_path("scenes/hertz-force.json"))
    assert r.status == contactqp.Status.CONVERGED
    (surface,) = r.reactions
    assert surface["boundary"] == "top"
    assert surface["displacement"][0] is None  # free at each node, as the push leaves it
    assert surface["displacement"][1] == pytest.approx(-0.016, rel=1e-6)
    assert -surface["force"][1] == pytest.approx(r.contact.total_force, rel=1e-8)


def test_a_moment_on_a_rigid_surface_reports_how_far_the_surface_turned():
    # scenes/block-moment.json: within the kern beam theory is exact with quadratic elements:
    # the top sinks by P H (1 - nu^2) / (E W) and turns by 12 H M (1 - nu^2) / (E W^3).
    r = contactqp.solve_scene(source_path("scenes/block-moment.json"))
    assert r.status == contactqp.Status.CONVERGED
    (surface,) = r.reactions
    assert surface["moment"] == 0.002
    assert surface["rotation"] == pytest.approx(12 * 0.002 * 0.91 / 8, rel=1e-8)
    assert surface["displacement"][1] == pytest.approx(-0.01 * 0.91 / 2, rel=1e-8)
    np.testing.assert_allclose(surface["about"], [0.0, 1.0], atol=1e-14)


def test_a_ball_between_two_plates_reports_how_far_it_moved_as_a_whole():
    # scenes/ball-between-plates.json: identical plates, the lower held, the upper's top moved by
    # d by the force; by the mirror symmetry about the ball's centre the ball moves by d/2.
    r = contactqp.solve_scene(source_path("scenes/ball-between-plates.json"))
    assert r.status == contactqp.Status.CONVERGED
    floating = {entry["body"]: entry["translation"] for entry in r.floating}
    assert set(floating) == {"ball", "upper_plate"}
    assert floating["ball"][0] is None  # the symmetry plane holds it along x
    (surface,) = [reaction for reaction in r.reactions if "displacement" in reaction]
    assert floating["ball"][1] == pytest.approx(surface["displacement"][1] / 2, rel=2e-3)
    for pair in r.pairs:
        assert abs(pair.force_on_node_body[1]) == pytest.approx(0.005, rel=1e-8)


def test_an_adaptive_scene_reports_its_cycles_as_the_json_does(tmp_path):
    # hertz.json from one element size and an "adapt" section: the cycles refine until the
    # estimated relative energy error is below the target; the result is the last cycle's.
    scene = json.loads(open(HERTZ).read())
    scene["body"]["mesh"] = {"size": 0.25, "contact_size": 0.25}
    scene["solver"] = {"backend": "active_set"}
    scene["adapt"] = {"target": 0.05}
    path = tmp_path / "adaptive.json"
    path.write_text(json.dumps(scene))
    r = contactqp.solve_scene(str(path))
    assert r.adaptive["met"]
    assert r.adaptive["stop"] == ""
    cycles = r.adaptive["cycles"]
    assert len(cycles) >= 3
    assert cycles[-1]["dofs"] == r.dofs
    assert cycles[-1]["relative"] <= 0.05 < cycles[0]["relative"]
    assert json.loads(r.json())["adaptive"]["cycles"][-1]["dofs"] == r.dofs
    assert "tangential_force" not in cycles[-1]  # friction's keys only with friction
    assert contactqp.solve_scene(HERTZ).adaptive is None


def test_a_frictional_adaptive_scene_reports_q_and_the_stick_zone_per_cycle(tmp_path):
    # sliding-block.json (Coulomb, load steps): every cycle reruns the path; each cycle has the
    # last step's tangential force and stick zone, the last cycle's the report's own.
    scene = json.loads(open(source_path("scenes/sliding-block.json")).read())
    scene["adapt"] = {"target": 0.03}
    path = tmp_path / "adaptive.json"
    path.write_text(json.dumps(scene))
    r = contactqp.solve_scene(str(path))
    cycles = r.adaptive["cycles"]
    assert r.adaptive["met"] and len(cycles) >= 2
    result = json.loads(r.json())
    assert [c["tangential_force"] for c in result["adaptive"]["cycles"]] == [c["tangential_force"] for c in cycles]
    assert cycles[-1]["tangential_force"] == pytest.approx(result["contact"]["tangential_force"], rel=1e-12)
    assert cycles[-1]["stick_zone"] == pytest.approx(result["contact"]["stick_half_width"], rel=1e-12, abs=1e-300)
    assert cycles[-1]["tangential_force"] > 0


def test_csv_and_vtu_equal_the_cli_files(tmp_path):
    csv, vtu = tmp_path / "p.csv", tmp_path / "m.vtu"
    run = subprocess.run([CLI, "solve", HERTZ, "--backend", "active_set", "--csv", str(csv), "--vtu", str(vtu)],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    r = contactqp.solve_scene(HERTZ, backend="active_set")
    assert r.csv() == csv.read_text()
    assert r.vtu() == vtu.read_text()


def test_no_contact_is_one_linear_solve():
    r = contactqp.solve_scene(HERTZ, no_contact=True)
    assert r.backend is None and r.no_contact and r.converged
    assert np.all(r.lam == 0) and r.hertz is None


def test_compare_scene_matches_cli_compare(tmp_path):
    expected, run = cli_json(tmp_path, "compare", HERTZ, "--tol", "1e-10")
    c = contactqp.compare_scene(HERTZ, tol=1e-10)
    assert c.agree == expected["agree"] == (run.returncode == 0)
    assert c.reference.label == expected["reference"]
    assert [run.backend.label for run in c.runs] == [r["backend"] for r in expected["runs"]]
    assert_same_numbers(json.loads(c.json()), expected)
    for mine, theirs in zip(c.runs, expected["runs"]):
        assert mine.contact.half_width == pytest.approx(theirs["half_width"], rel=1e-12)
        assert mine.rel_diff_u == pytest.approx(theirs["rel_diff_u"], rel=1e-9, abs=1e-16)
    pair = contactqp.compare_scene(HERTZ, backends=["active_set", contactqp.Backend.UZAWA], tol=1e-10)
    assert [r.backend for r in pair.runs] == [contactqp.Backend.ACTIVE_SET, contactqp.Backend.UZAWA]
    assert pair.agree and pair.max_diff_u <= pair.bound["u"]


def test_the_gil_is_released_during_a_solve():
    """Another Python thread runs while a scene is meshed and solved."""
    counter = [0]
    done = threading.Event()

    def work():
        contactqp.solve_scene(HERTZ, backend="uzawa", tol=1e-12)
        done.set()

    thread = threading.Thread(target=work)
    thread.start()
    while not done.is_set():
        counter[0] += 1
    thread.join()
    # Holding the GIL for the ~0.2 s of the solve would leave this loop a few switch intervals
    # (5 ms each); released, it spins freely.
    assert counter[0] > 10000
