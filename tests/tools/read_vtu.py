#!/usr/bin/python3
"""Reads a .vtu file with VTK (Debian's python3-vtk9) and prints what it holds as JSON, for the
Catch2 tests of `contactqp solve --vtu`: point and cell counts, cell types, and per point-data
array its components, tuples, whether every value is finite, and each component's min and max.
Exits 1 when VTK cannot read the file."""
import json
import sys

import numpy
# The reader alone: `import vtk` loads every VTK module, 0.5 s more per call.
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader


def main(path):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if reader.GetErrorCode() != 0 or grid is None or grid.GetNumberOfPoints() == 0:
        print(f"VTK could not read {path}", file=sys.stderr)
        return 1
    out = {
        "points": grid.GetNumberOfPoints(),
        "cells": grid.GetNumberOfCells(),
        "cell_types": sorted({grid.GetCellType(i) for i in range(grid.GetNumberOfCells())}),
        "arrays": {},
    }
    data = grid.GetPointData()
    for i in range(data.GetNumberOfArrays()):
        array = data.GetArray(i)
        values = vtk_to_numpy(array).reshape(array.GetNumberOfTuples(), array.GetNumberOfComponents())
        out["arrays"][array.GetName()] = {
            "components": array.GetNumberOfComponents(),
            "tuples": array.GetNumberOfTuples(),
            "finite": bool(numpy.isfinite(values).all()),
            "min": [float(v) for v in values.min(axis=0)],
            "max": [float(v) for v in values.max(axis=0)],
        }
    print(json.dumps(out))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
