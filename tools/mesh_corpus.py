#!/usr/bin/python3
"""Seeds for the mesh-file fuzzer (fuzz/fuzz_mesh.cpp): the meshes of the shipped scenes, made
coarse (a few hundred elements, so that each run of the fuzzer stays fast; meshes above
64 KB and repeats are left out), in every format the
reader takes — .msh 4.1 and 2.2, binary and ASCII. The generated bodies come from `contactqp mesh`
(its own 4.1 binary writer) with the scene's mesh sizes multiplied; the .geo files of scenes/ are
meshed by the gmsh program at a coarser size; gmsh converts each to the other three formats.

usage: tools/mesh_corpus.py CONTACTQP OUT_DIR    (from the repository root; needs the gmsh program)"""
import hashlib
import json
import os
import subprocess
import sys
import tempfile

FORMATS = [("41b", ["-format", "msh41", "-bin"]), ("41a", ["-format", "msh41"]),
           ("22b", ["-format", "msh22", "-bin"]), ("22a", ["-format", "msh22"])]


def gmsh(arguments):
    subprocess.run(["gmsh"] + arguments, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def coarse(body, factor):
    """The body's mesh request with sizes `factor` times larger (contact_size at most size)."""
    mesh = dict(body.get("mesh", {}))
    if "size" in mesh:
        mesh["size"] *= factor
        mesh["contact_size"] = min(mesh["size"], mesh["contact_size"] * 10 * factor)
    mesh.pop("refinements", None)
    return dict(body, mesh=mesh)


def main(cli, out_dir):
    os.makedirs(out_dir, exist_ok=True)
    made = []
    seen = set()
    with tempfile.TemporaryDirectory() as work:
        for name in sorted(os.listdir("scenes")):
            path = os.path.join("scenes", name)
            stem, ext = os.path.splitext(name)
            first = os.path.join(work, stem + ".msh")
            if ext == ".json":
                with open(path) as file:
                    scene = json.load(file)
                if "body" not in scene or scene["body"].get("shape") == "mesh":
                    continue  # several bodies, or already a file (its .geo is meshed below)
                scene["body"] = coarse(scene["body"], 4)
                coarse_scene = os.path.join(work, name)
                with open(coarse_scene, "w") as file:
                    json.dump(scene, file)
                done = subprocess.run([cli, "mesh", coarse_scene, "-o", first], capture_output=True, text=True)
                if done.returncode != 0:
                    print("skipped %s: %s" % (name, done.stderr.strip()), file=sys.stderr)
                    continue
            elif ext == ".geo":
                with open(path) as file:
                    volume = "Volume" in file.read()
                gmsh([path, "-3" if volume else "-2", "-clscale", "4", "-format", "msh41", "-bin", "-o", first])
            else:
                continue
            with open(first, "rb") as file:
                content = file.read()
            if len(content) > 64 * 1024 or hashlib.sha256(content).digest() in seen:
                continue
            seen.add(hashlib.sha256(content).digest())
            for tag, options in FORMATS:
                target = os.path.join(out_dir, "%s-%s.msh" % (stem, tag))
                gmsh([first, "-save"] + options + ["-o", target])
                made.append(target)
    sizes = [os.path.getsize(path) for path in made]
    print("%d seeds in %s, %d to %d bytes" % (len(made), out_dir, min(sizes), max(sizes)))
    return 0 if made else 1


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2]))
