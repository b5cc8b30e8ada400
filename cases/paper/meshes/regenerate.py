"""Regenerates the unstructured Gmsh meshes of the paper cases
(`cargo xtask fixtures` runs it). The cases and `cargo xtask validate` read
the committed .msh files; Gmsh is needed only to remake them.

Needs Gmsh from PyPI (`pip install gmsh`; tested with 4.15.2).

- cube-<h>mm.msh: the polyaxial test's 0.5 m cube (Guo et al. §3.2), one
  physical volume `cube` and one physical surface per face (`xmin` … `zmax`),
  Gmsh's Delaunay mesher with Netgen optimisation at a uniform target size
  h. h = 22 mm gives ~51,000 tets of mean edge ~27 mm (the paper: 55,435
  tets, mean ~27 mm, smallest ~17 mm); h = 50 mm is the quick profile's.
- disc-<h>mm.msh: the Brazilian disc (§3.1), 40 mm across and 15 mm thick,
  one physical volume `disc`, at target size h (4 mm: 1,823 tets; 2 mm:
  10,950; 1.2 mm, the paper's size: see the file): the unstructured
  alternative to the extruded prisms, for `cargo xtask validate
  --sensitivity` and the paper's mesh type at the paper's size.
"""

import os

import gmsh

here = os.path.dirname(os.path.abspath(__file__))
EDGE = 0.5  # m


def mesh_and_write(name, h, h_min=None):
    """Meshes the current model at target size h (m; down to h_min where a
    size field asks for it) with Gmsh's Delaunay mesher and Netgen
    optimisation, writes <name>.msh (MSH 4.1 ASCII, physical groups only)
    beside this script, and removes the model."""
    gmsh.option.setNumber("Mesh.MeshSizeMin", h if h_min is None else h_min)
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    gmsh.option.setNumber("Mesh.Algorithm3D", 1)
    gmsh.model.mesh.generate(3)
    gmsh.model.mesh.optimize("Netgen")
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 0)
    gmsh.option.setNumber("Mesh.SaveAll", 0)
    path = os.path.join(here, f"{name}.msh")
    gmsh.write(path)
    tets, _ = gmsh.model.mesh.getElementsByType(4)
    print(f"{os.path.basename(path)}: {len(tets)} tets")
    gmsh.model.remove()


def cube(h_mm):
    h = 1e-3 * h_mm
    gmsh.model.add(f"cube-{h_mm}mm")
    v = gmsh.model.occ.addBox(0, 0, 0, EDGE, EDGE, EDGE)
    gmsh.model.occ.synchronize()
    gmsh.model.addPhysicalGroup(3, [v], name="cube")
    for dim, tag in gmsh.model.getBoundary([(3, v)], oriented=False):
        c = gmsh.model.occ.getCenterOfMass(dim, tag)
        for k, axis in enumerate("xyz"):
            if abs(c[k]) < 1e-9:
                gmsh.model.addPhysicalGroup(2, [tag], name=axis + "min")
            if abs(c[k] - EDGE) < 1e-9:
                gmsh.model.addPhysicalGroup(2, [tag], name=axis + "max")
    mesh_and_write(f"cube-{h_mm}mm", h)


def disc(h_mm, name=None, turn=0.0):
    """The disc at target size h_mm; `turn` (radians) turns the geometry
    about its axis before meshing: the same disc meshed differently where
    the platens touch it (a second mesh "seed")."""
    h = 1e-3 * h_mm
    name = name or f"disc-{h_mm}mm"
    gmsh.model.add(name)
    v = gmsh.model.occ.addCylinder(0, 0, 0, 0, 0, 0.015, 0.020)
    if turn:
        gmsh.model.occ.rotate([(3, v)], 0, 0, 0, 0, 0, 1, turn)
    gmsh.model.occ.synchronize()
    gmsh.model.addPhysicalGroup(3, [v], name="disc")
    mesh_and_write(name, h)


def disc_refined(h_mm, fine_mm, depth_mm, name):
    """The disc at target size h_mm, refined to fine_mm within depth_mm of
    the loaded points (y = ±20 mm), where the platens crush it."""
    h, fine, depth = 1e-3 * h_mm, 1e-3 * fine_mm, 1e-3 * depth_mm
    gmsh.model.add(name)
    v = gmsh.model.occ.addCylinder(0, 0, 0, 0, 0, 0.015, 0.020)
    gmsh.model.occ.synchronize()
    gmsh.model.addPhysicalGroup(3, [v], name="disc")
    boxes = []
    for sign in (1, -1):
        f = gmsh.model.mesh.field.add("Box")
        gmsh.model.mesh.field.setNumber(f, "VIn", fine)
        gmsh.model.mesh.field.setNumber(f, "VOut", h)
        gmsh.model.mesh.field.setNumber(f, "XMin", -0.021)
        gmsh.model.mesh.field.setNumber(f, "XMax", 0.021)
        y0, y1 = sorted((sign * (0.020 - depth), sign * 0.021))
        gmsh.model.mesh.field.setNumber(f, "YMin", y0)
        gmsh.model.mesh.field.setNumber(f, "YMax", y1)
        gmsh.model.mesh.field.setNumber(f, "ZMin", -0.001)
        gmsh.model.mesh.field.setNumber(f, "ZMax", 0.016)
        gmsh.model.mesh.field.setNumber(f, "Thickness", h)
        boxes.append(f)
    m = gmsh.model.mesh.field.add("Min")
    gmsh.model.mesh.field.setNumbers(m, "FieldsList", boxes)
    gmsh.model.mesh.field.setAsBackgroundMesh(m)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    mesh_and_write(name, h, fine)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 1)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 1)


gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
for size in (50, 22):
    cube(size)
for size in (4, 2, 1.2):
    disc(size)
disc(1.2, "disc-1.2mm-turned", turn=0.3)
disc_refined(1.2, 0.6, 3.0, "disc-1.2mm-platens-0.6mm")
gmsh.finalize()
