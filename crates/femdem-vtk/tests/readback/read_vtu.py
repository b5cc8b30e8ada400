"""Independent reader for femdem-vtk's readback test.

Usage: read_vtu.py MANIFEST.json

The manifest is {"vtu": [{"path": ..., "meshio": bool}], "pvd": [path, ...]}.
Every .vtu is read with VTK's own XML reader (what ParaView uses) and, where
"meshio" is true, with meshio. Every .pvd is parsed with xml.etree. Arrays
come back as hex strings of their little-endian bytes (float64 or int64), so
that the Rust side compares them bit for bit. The result is printed as one
line: "FEMDEM-JSON " followed by JSON.
"""

import json
import sys
import xml.etree.ElementTree as ET

import numpy as np


def hexf(a):
    return np.ascontiguousarray(a, dtype="<f8").tobytes().hex()


def hexi(a):
    return np.ascontiguousarray(a, dtype="<i8").tobytes().hex()


def read_vtk(path):
    from vtkmodules.util.misc import calldata_type
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.util.vtkConstants import VTK_STRING
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

    messages = []

    @calldata_type(VTK_STRING)
    def on_message(_obj, _event, message):
        messages.append(message)

    reader = vtkXMLUnstructuredGridReader()
    reader.AddObserver("ErrorEvent", on_message)
    reader.AddObserver("WarningEvent", on_message)
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    n_points = grid.GetNumberOfPoints()
    n_cells = grid.GetNumberOfCells()
    points = (
        vtk_to_numpy(grid.GetPoints().GetData()) if grid.GetPoints() else np.zeros((0, 3))
    )
    cells = grid.GetCells()

    def arrays(data):
        out = {}
        for i in range(data.GetNumberOfArrays()):
            a = data.GetArray(i)
            out[a.GetName()] = {
                "components": a.GetNumberOfComponents(),
                "type": a.GetDataTypeAsString(),
                "values": hexf(vtk_to_numpy(a)),
            }
        return out

    return {
        "messages": messages,
        "num_points": n_points,
        "num_cells": n_cells,
        "points": hexf(points),
        "types": [int(t) for t in vtk_to_numpy(grid.GetCellTypesArray())]
        if n_cells
        else [],
        "offsets": hexi(vtk_to_numpy(cells.GetOffsetsArray())) if cells else "",
        "connectivity": hexi(vtk_to_numpy(cells.GetConnectivityArray()))
        if cells
        else "",
        "point_data": arrays(grid.GetPointData()),
        "cell_data": arrays(grid.GetCellData()),
    }


def read_meshio(path):
    import meshio

    try:
        mesh = meshio.read(path)
    except Exception as e:  # reported to the Rust side, which decides
        return {"error": f"{type(e).__name__}: {e}"}

    def field(v):
        v = np.asarray(v)
        return {
            "components": 1 if v.ndim == 1 else int(np.prod(v.shape[1:])),
            "type": str(v.dtype),
            "values": hexf(v),
        }

    return {
        "points": hexf(mesh.points),
        "cells": [{"type": c.type, "connectivity": hexi(c.data)} for c in mesh.cells],
        "point_data": {k: field(v) for k, v in mesh.point_data.items()},
        # One cell block (all tets): take the first block of each field.
        "cell_data": {k: field(v[0]) for k, v in mesh.cell_data.items()},
    }


def read_pvd(path):
    root = ET.parse(path).getroot()
    return {
        "root": root.tag,
        "type": root.get("type"),
        "datasets": [
            {"timestep": d.get("timestep"), "file": d.get("file"), "part": d.get("part")}
            for d in root.iter("DataSet")
        ],
        "collections": len(root.findall("Collection")),
    }


def main():
    with open(sys.argv[1]) as f:
        manifest = json.load(f)
    import meshio
    import vtkmodules

    result = {
        "versions": {
            "python": sys.version.split()[0],
            "numpy": np.__version__,
            "meshio": meshio.__version__,
            "vtk": vtkmodules.__version__,
        },
        "vtu": {},
        "pvd": {},
    }
    for item in manifest["vtu"]:
        path = item["path"]
        entry = {"vtk": read_vtk(path)}
        if item["meshio"]:
            entry["meshio"] = read_meshio(path)
        result["vtu"][path] = entry
    for path in manifest["pvd"]:
        result["pvd"][path] = read_pvd(path)
    print("FEMDEM-JSON " + json.dumps(result))


if __name__ == "__main__":
    main()
