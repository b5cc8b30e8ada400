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


def mesh_and_write(name, h):
    """Meshes the current model at uniform target size h (m) with Gmsh's
    Delaunay mesher and Netgen optimisation, writes <name>.msh (MSH 4.1
    ASCII, physical groups only) beside this script, and removes the model."""
    gmsh.option.setNumber("Mesh.MeshSizeMin", h)
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


def disc(h_mm):
    h = 1e-3 * h_mm
    gmsh.model.add(f"disc-{h_mm}mm")
    v = gmsh.model.occ.addCylinder(0, 0, 0, 0, 0, 0.015, 0.020)
    gmsh.model.occ.synchronize()
    gmsh.model.addPhysicalGroup(3, [v], name="disc")
    mesh_and_write(f"disc-{h_mm}mm", h)


gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
for size in (50, 22):
    cube(size)
for size in (4, 2, 1.2):
    disc(size)
gmsh.finalize()
