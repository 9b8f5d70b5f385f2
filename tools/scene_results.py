#!/usr/bin/python3
"""Runs every shipped scene (scenes/*.json but hertz-sphere-large, which needs a big machine) with
`contactqp solve SCENE --json --csv --vtu` and keeps what a refactoring must not change: the
result JSON without its timings (every key named "timings", and every key with "seconds" in its
name), and a SHA-256 of the profile CSV and of the ParaView file (which holds the stresses the
JSON does not). With --against, compares with an earlier run's directory and exits 1 on any
difference, printing the differing fields.

With --variants, also runs variants of the shipped scenes that reach what they do not: traction,
pressure and gravity on 3- and 6-node triangles and 4- and 10-node tetrahedra, and transformed
scenes with every kind of obstacle (written under OUT_DIR/variants; the scene's own path in the
result is reduced to its file name so that two runs compare).

usage:
  tools/scene_results.py CONTACTQP OUT_DIR [--variants | --only-variants] # record
  tools/scene_results.py CONTACTQP OUT_DIR [--variants] --against BASE    # record and compare with BASE

Run it from the repository root (scene paths in the JSON are then the same in both runs), once
before a change with the old binary and once after with the new one, e.g.
  tools/scene_results.py build/contactqp /tmp/before
  ... change, rebuild ...
  tools/scene_results.py build/contactqp /tmp/after --against /tmp/before"""
import hashlib
import json
import os
import subprocess
import sys
import tempfile

SKIPPED = {"hertz-sphere-large.json"}

FORCES_2D = [{"type": "gravity", "density": 1.0, "g": [0.0, -1e-3]},
             {"type": "pressure", "boundary": "arc", "value": 1e-4},
             {"type": "traction", "boundary": "arc", "value": [0.0, -1e-4]}]
FORCES_3D = [{"type": "gravity", "density": 1.0, "g": [0.0, 0.0, -1e-3]},
             {"type": "pressure", "boundary": "surface", "value": 1e-5},
             {"type": "traction", "boundary": "surface", "value": [0.0, 0.0, -1e-5]}]
# With a force among the loads every facing node is a candidate unless contact.max_gap says
# otherwise: the variants keep the shipped scenes' candidates (1.5 times the push).
GAP_2D, GAP_3D = {"max_gap": 0.024}, {"max_gap": 0.015}
VARIANTS = {  # name: (shipped scene, merge patch; a "load" list is added to the scene's load)
    "forces-tri3": ("hertz.json", {"load": FORCES_2D, "contact": GAP_2D}),
    "forces-tri6": ("hertz-order2.json", {"load": FORCES_2D, "contact": GAP_2D}),
    "forces-tet4": ("hertz-sphere.json", {"load": FORCES_3D, "body": {"mesh": {"order": 1}}, "contact": GAP_3D}),
    "forces-tet10": ("hertz-sphere.json", {"load": FORCES_3D, "contact": GAP_3D}),
    "forces-box-tet10": ("punch.json", {"load": [{"type": "gravity", "density": 1.0, "g": [0.0, 0.0, -1e-3]},
                                                {"type": "traction", "boundary": "right", "value": [0, 0, 1e-5]}],
                                       "contact": GAP_3D}),
    "turned-circle": ("block-on-circle.json", {"transform": {"rotate_degrees": 17.0}}),
    "turned-profile": ("hertz.json", {"transform": {"rotate_degrees": 25.0},
                                      "obstacle": {"type": "profile", "points": [[-1.0, 0.0], [1.0, 0.0]],
                                                   "body_side": "left", "point": None, "normal": None}}),
    "turned-sphere": ("hertz-sphere.json", {"transform": {"axis": [1.0, 1.0, 1.0], "rotate_degrees": 40.0},
                                            "obstacle": {"type": "sphere", "center": [0.0, 0.0, -10.0],
                                                         "radius": 10.0, "point": None, "normal": None}}),
    "turned-cylinder": ("hertz-sphere.json", {"transform": {"axis": [0.0, 1.0, 0.0], "rotate_degrees": 90.0},
                                              "obstacle": {"type": "cylinder", "point": [0.0, 0.0, -10.0],
                                                           "axis": [1.0, 0.0, 0.0], "radius": 10.0,
                                                           "normal": None}}),
    "turned-punch": ("punch.json", {"transform": {"axis": [0.0, 1.0, 0.0], "rotate_degrees": 10.0}}),
}


def write_variants(directory):
    os.makedirs(directory, exist_ok=True)
    paths = []
    for name, (base, patch) in sorted(VARIANTS.items()):
        with open(os.path.join("scenes", base)) as file:
            scene = json.load(file)
        patch = dict(patch)
        if "load" in patch:
            loads = scene["load"] if isinstance(scene["load"], list) else [scene["load"]]
            scene["load"] = loads + patch.pop("load")
        merge(scene, patch)
        path = os.path.join(directory, name + ".json")
        with open(path, "w") as file:
            json.dump(scene, file, indent=1)
        paths.append(path)
    return paths


def merge(target, patch):
    """JSON Merge Patch (RFC 7386): None removes a key."""
    for key, value in patch.items():
        if value is None:
            target.pop(key, None)
        elif isinstance(value, dict) and isinstance(target.get(key), dict):
            merge(target[key], value)
        else:
            target[key] = value


def without_timings(value):
    if isinstance(value, dict):
        return {key: without_timings(item) for key, item in value.items() if key != "timings" and "seconds" not in key}
    if isinstance(value, list):
        return [without_timings(item) for item in value]
    return value


def digest(path):
    with open(path, "rb") as file:
        return hashlib.sha256(file.read()).hexdigest()


def record(cli, scene, out_dir):
    name = os.path.splitext(os.path.basename(scene))[0]
    with tempfile.TemporaryDirectory() as work:
        paths = {ext: os.path.join(work, name + "." + ext) for ext in ("json", "csv", "vtu")}
        done = subprocess.run([cli, "solve", scene, "--quiet", "--json", paths["json"], "--csv", paths["csv"],
                               "--vtu", paths["vtu"]], capture_output=True, text=True)
        kept = {"exit_status": done.returncode, "stderr": done.stderr}
        if os.path.exists(paths["json"]):
            with open(paths["json"]) as file:
                kept["result"] = without_timings(json.load(file))
            source = kept["result"].get("scene", {}).get("source")
            if source:
                kept["result"]["scene"]["source"] = os.path.basename(source)
        for ext in ("csv", "vtu"):
            if os.path.exists(paths[ext]):
                kept[ext + "_sha256"] = digest(paths[ext])
    with open(os.path.join(out_dir, name + ".json"), "w") as file:
        json.dump(kept, file, indent=1, sort_keys=True)
    return kept


def differences(a, b, path=""):
    if isinstance(a, dict) and isinstance(b, dict):
        out = []
        for key in sorted(set(a) | set(b)):
            if key not in a or key not in b:
                out.append("%s.%s: only in %s" % (path, key, "the earlier run" if key in a else "this run"))
            else:
                out += differences(a[key], b[key], path + "." + key)
        return out
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        out = []
        for i, (x, y) in enumerate(zip(a, b)):
            out += differences(x, y, "%s[%d]" % (path, i))
        return out
    return [] if a == b else ["%s: %s -> %s" % (path, json.dumps(a)[:80], json.dumps(b)[:80])]


def main(arguments):
    variants = "--variants" in arguments or "--only-variants" in arguments
    shipped = "--only-variants" not in arguments
    arguments = [a for a in arguments if a not in ("--variants", "--only-variants")]
    if len(arguments) not in (2, 4) or (len(arguments) == 4 and arguments[2] != "--against"):
        print(__doc__)
        return 2
    cli, out_dir = arguments[0], arguments[1]
    base = arguments[3] if len(arguments) == 4 else None
    os.makedirs(out_dir, exist_ok=True)
    scenes = sorted(os.path.join("scenes", name) for name in os.listdir("scenes")
                    if name.endswith(".json") and name not in SKIPPED and shipped)
    if variants:
        scenes += write_variants(os.path.join(out_dir, "variants"))
    changed = 0
    for scene in scenes:
        kept = record(cli, scene, out_dir)
        line = "%-28s exit %d" % (scene, kept["exit_status"])
        if base:
            with open(os.path.join(base, os.path.basename(scene))) as file:
                before = json.load(file)
            found = differences(before, kept)
            line += ": " + ("unchanged" if not found else "%d differences" % len(found))
            changed += bool(found)
            for text in found[:20]:
                line += "\n    " + text
        print(line, flush=True)
    if base:
        print("%d of %d scenes changed" % (changed, len(scenes)))
    return 1 if changed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
