"""SceneResult.pairs and .bodies: the shipped two-body scenes, solved from Python, against the
command line's JSON, Newton's third law, the supports' reactions and Hertz for two cylinders
computed here from the scene file's radii and moduli."""
import json
import math

import numpy as np
import pytest

import contactqp
from conftest import assert_same_numbers, cli_json, source_path

SCENES = ["scenes/two-cylinders.json", "scenes/roller-on-block.json"]


def pair_as_json(pair, dim):
    """A PairResult in the shape of the result JSON's pairs[i] (result_json.cpp)."""
    entry = {
        "node_side": pair.node_side,
        "face_side": pair.face_side,
        "side_rule": pair.side_rule,
        "rows": pair.rows,
        "force_on_node_body": pair.force_on_node_body.tolist(),
        "force_on_face_body": pair.force_on_face_body.tolist(),
        "action_reaction_residual": pair.action_reaction_residual,
        "total_force": pair.total_force,
        "max_pressure": pair.max_pressure,
        "max_nodal_pressure": pair.max_nodal_pressure,
        "face_max_pressure": pair.face_max_pressure,
        "contact_nodes": pair.contact_nodes,
        "slipped_nodes": pair.slipped_nodes,
        "max_slip": pair.max_slip,
        "profile": pair.profile.tolist(),
        "face_profile": pair.face_profile.tolist(),
    }
    if dim == 2:
        entry.update(line_load=pair.line_load, half_width=pair.half_width,
                     half_width_last_node=pair.half_width_last_node)
    else:
        entry.update(contact_area=pair.contact_area, contact_radius=pair.contact_radius,
                     contact_radius_last_node=pair.contact_radius_last_node)
    h = pair.hertz
    if h is not None:
        entry["hertz"] = {"radius": h.radius, "radius_source": h.radius_source, "max_pressure": h.max_pressure,
                          "effective_modulus": h.effective_modulus, "error_max_pressure": h.error_max_pressure,
                          "error_l2": h.error_l2}
        if h.dim == 2:
            entry["hertz"].update(half_width=h.half_width, error_half_width=h.error_half_width)
        else:
            entry["hertz"].update(force=h.force, contact_radius=h.contact_radius,
                                  error_contact_radius=h.error_contact_radius)
    return entry


def body_as_json(body):
    return {"name": body.name, "shape": body.shape, "E": body.E, "nu": body.nu, "nodes": body.nodes,
            "elements": body.elements, "contact_force": body.contact_force.tolist()}


@pytest.fixture(scope="module", params=SCENES, ids=lambda s: s.split("/")[-1])
def solved(request, tmp_path_factory):
    """One scene solved by Python and by the command line, with the scene's own solver section."""
    path = source_path(request.param)
    expected, _ = cli_json(tmp_path_factory.mktemp("cli"), "solve", path)
    with open(path) as f:
        scene = json.load(f)
    return contactqp.solve_scene(path), expected, scene


def test_pairs_and_bodies_equal_the_cli_json(solved):
    r, expected, _ = solved
    assert r.converged and expected["status"] == "converged"
    dim = len(expected["pairs"][0]["force_on_node_body"])
    # Every key of the JSON's pairs[i] and bodies[i] has its attribute, to round-off.
    assert len(r.pairs) == len(expected["pairs"]) == 1
    for pair, entry in zip(r.pairs, expected["pairs"]):
        assert_same_numbers(pair_as_json(pair, dim), entry)
    assert [b.name for b in r.bodies] == [b["name"] for b in expected["bodies"]]
    for body, entry in zip(r.bodies, expected["bodies"]):
        assert_same_numbers(body_as_json(body), entry)
    # The profiles are numpy arrays sorted by s, the nodal forces and nodes beside them.
    pair = r.pairs[0]
    assert isinstance(pair.profile, np.ndarray) and pair.profile.shape == (len(pair.profile_force), 2)
    assert np.all(np.diff(pair.profile[:, 0]) >= 0) and np.all(np.diff(pair.face_profile[:, 0]) >= 0)
    assert pair.face_profile.shape == (len(pair.face_profile_force), 2)
    # The node side's nodes belong to the node side's body, the face side's to the other.
    for nodes, body in ((pair.profile_node, r.bodies[pair.node_body]), (pair.face_profile_node, r.bodies[pair.face_body])):
        assert np.all((nodes >= body.first_node) & (nodes < body.first_node + body.nodes))
    assert sum(b.nodes for b in r.bodies) == r.nodes and sum(b.elements for b in r.bodies) == r.elements
    # The rows' forces are the multipliers: Σλ over the half model, doubled by the symmetry plane.
    assert pair.total_force == pytest.approx(2 * r.lam.sum(), rel=1e-12)
    assert pair.total_force == pytest.approx(2 * pair.profile_force.sum(), rel=1e-12)
    # And the rest of the file too, through the report's own json().
    assert_same_numbers(json.loads(r.json()), expected)


def test_action_equals_reaction_and_the_supports_balance(solved):
    r, _, _ = solved
    pair = r.pairs[0]
    a, b = pair.force_on_node_body, pair.force_on_face_body
    scale = max(np.linalg.norm(a), np.linalg.norm(b))
    assert scale > 0
    assert np.linalg.norm(a + b) / scale <= 1e-10
    assert pair.action_reaction_residual <= 1e-10
    assert np.linalg.norm(sum(body.contact_force for body in r.bodies)) / scale <= 1e-10
    # Each body's supports (K u - f at its loaded boundary, not the multipliers) hold its contact force.
    for body in r.bodies:
        reaction = sum(x["force"] for x in r.reactions if x["boundary"].startswith(body.name + "."))
        np.testing.assert_allclose(reaction + body.contact_force, 0, atol=1e-8 * scale)


def hertz_two_cylinders(scene, line_load):
    """b and p0 of two cylinders in plane strain (a flat body: 1/R2 = 0), from the scene file."""
    assert scene["model"] == "plane_strain"
    curvature = sum(1 / body["radius"] for body in scene["bodies"] if body["shape"] == "half_disc")
    compliance = sum((1 - body["material"]["nu"] ** 2) / body["material"]["E"] for body in scene["bodies"])
    R, E_star = 1 / curvature, 1 / compliance
    b = math.sqrt(4 * line_load * R / (math.pi * E_star))
    return R, E_star, b, 2 * line_load / (math.pi * b)


def test_b_and_p0_within_3_percent_of_hertz(solved):
    r, _, scene = solved
    pair = r.pairs[0]
    thickness = scene["bodies"][0].get("thickness", 1.0)
    P = np.linalg.norm(pair.force_on_node_body) / thickness
    assert P == pytest.approx(pair.line_load, rel=1e-12)
    R, E_star, b, p0 = hertz_two_cylinders(scene, P)
    assert abs(pair.half_width / b - 1) <= 0.03, (pair.half_width, b)
    assert abs(pair.max_pressure / p0 - 1) <= 0.03, (pair.max_pressure, p0)
    # The library's own comparison computes the same closed form and the same errors.
    h = pair.hertz
    assert (h.radius, h.effective_modulus) == (pytest.approx(R, rel=1e-12), pytest.approx(E_star, rel=1e-12))
    assert (h.half_width, h.max_pressure) == (pytest.approx(b, rel=1e-12), pytest.approx(p0, rel=1e-12))
    assert h.error_half_width == pytest.approx(pair.half_width / b - 1, rel=1e-9)
    assert h.error_max_pressure == pytest.approx(pair.max_pressure / p0 - 1, rel=1e-9)
    # The L2 error of the node side's profile against p0 sqrt(1 - s²/b²) (trapezoidal rule,
    # centre at s = 0 by symmetry): the same number, and below 3 %.
    s, p = pair.profile[:, 0], pair.profile[:, 1]
    exact = p0 * np.sqrt(np.clip(1 - (s / b) ** 2, 0, None))
    l2 = math.sqrt(np.trapz((p - exact) ** 2, s) / np.trapz(exact**2, s))
    assert h.error_l2 == pytest.approx(l2, rel=1e-9) and l2 <= 0.03
    # The face side carries the same pressure, seen from the other body.
    s_face, p_face = pair.face_profile[:, 0], pair.face_profile[:, 1]
    exact_face = p0 * np.sqrt(np.clip(1 - (s_face / b) ** 2, 0, None))
    assert math.sqrt(np.trapz((p_face - exact_face) ** 2, s_face) / np.trapz(exact_face**2, s_face)) <= 0.03


def test_max_pressure_is_the_whole_bodys_three_node_patch_average(solved):
    """docs/bodies.md: a pair's 2D max_pressure is the largest (lam_{i-1} + lam_i + lam_{i+1}) /
    (w_{i-1} + w_i + w_{i+1}) along the whole body's profile; the half model's profile is
    mirrored about the symmetry plane, where its node counts with its image (twice the force
    over twice the tributary). Computed here from the profile: w_i = lam_i / p_i."""
    r, _, _ = solved
    pair = r.pairs[0]
    s, p, f = pair.profile[:, 0], pair.profile[:, 1], pair.profile_force
    assert s[0] == 0 and np.all(s[1:] > 0)  # both scenes are half models with a node on the plane
    w = np.where(p > 0, f / np.where(p > 0, p, 1), np.nan)  # unloaded nodes: unknown, not needed
    whole_f = np.concatenate([f[:0:-1], [2 * f[0]], f[1:]])
    whole_w = np.concatenate([w[:0:-1], [2 * w[0]], w[1:]])
    patches = (whole_f[:-2] + whole_f[1:-1] + whole_f[2:]) / (whole_w[:-2] + whole_w[1:-1] + whole_w[2:])
    assert pair.max_pressure == pytest.approx(np.nanmax(patches), rel=1e-12)
    assert pair.max_nodal_pressure == pytest.approx(p.max(), rel=1e-12)
    # The one-body definition, for comparison: the nodal maximum.
    one = contactqp.solve_scene(source_path("scenes/hertz.json"), backend="active_set")
    assert one.contact.max_pressure == pytest.approx(one.contact.profile[:, 1].max(), rel=1e-15)


def test_a_one_body_scene_has_no_pairs():
    r = contactqp.solve_scene(source_path("scenes/hertz.json"), backend="active_set")
    assert r.pairs == [] and r.bodies == []
