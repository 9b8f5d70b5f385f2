#!/usr/bin/python3
"""The folders of src/ in one order, lowest first (docs/style.md, "Layers"): a file may include
the internal headers of its own folder and of the folders below it, never of one above. Folders
on one line are one layer (one library that their files share). solvers/ (the backends) sees
only qp/. Prints every upward include as FILE:LINE: FOLDER includes HEADER (above it) and exits
1 (a folder of src/ missing from the order too); nothing and 0 when every arrow points down.

usage: check_layers.py [REPOSITORY]"""
import os
import re
import sys

LAYERS = [
    ["qp"],           # the QP vocabulary, the certificate, the registries (cqp_qp)
    ["scene"],        # the scene read and checked; input files
    ["mesh"],         # meshes, their readers and refinement, the reference elements
    ["fe"],           # element matrices, K, force loads
    ["contact"],      # obstacles, candidate rows, pairs, friction rows
    ["model"],        # the model built from a scene and its QP assembled
    ["post"],         # post-processing of a solved model
    ["io"],           # results written (JSON, CSV, VTU)
    ["run"],          # run_scene(), compare_scene() (cqp_run)
    ["distributed", "petsc"],  # the PETSc room (cqp_petsc)
    ["cli"],          # the program
]
OTHERS = {"solvers": 0}  # solvers/ may reach qp/ alone
INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/')


def level_of(folder):
    for level, names in enumerate(LAYERS):
        if folder in names:
            return level
    return None


def main(root="."):
    upward = []
    checked = [(os.path.join(root, "src", folder), folder) for names in LAYERS for folder in names]
    checked.append((os.path.join(root, "solvers"), "solvers"))
    for directory, folder in checked:
        own = OTHERS.get(folder, level_of(folder))
        for parent, _, files in os.walk(directory):
            for name in sorted(files):
                if not name.endswith((".cpp", ".hpp", ".h")):
                    continue
                path = os.path.join(parent, name)
                with open(path, encoding="utf-8") as file:
                    for number, line in enumerate(file, 1):
                        match = INCLUDE.match(line)
                        if not match:
                            continue
                        level = level_of(match.group(1))
                        if level is not None and level > own:
                            upward.append("%s:%d: %s includes %s (above it)" %
                                          (os.path.relpath(path, root), number, folder, line.strip()[9:]))
    src = os.path.join(root, "src")
    for folder in sorted(os.listdir(src)) if os.path.isdir(src) else []:
        if os.path.isdir(os.path.join(src, folder)) and level_of(folder) is None:
            upward.append("src/%s: a folder that the order in tools/check_layers.py does not place" % folder)
    for line in upward:
        print(line)
    return 1 if upward else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:2]))
