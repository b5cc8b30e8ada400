"""Regenerates gmsh_two_volumes.msh (ASCII) and its binary twin
gmsh_two_volumes_binary.msh (the same mesh, written by Gmsh in binary, in
this machine's byte order: little-endian on x86 and ARM) from
gmsh_two_volumes.geo, and prints the counts that tests/msh.rs asserts
(elements per physical group, by type, and the volume of each physical
volume from Gmsh's own node coordinates). The numbers measured with Gmsh
4.15.2 are recorded in the header of gmsh_two_volumes.geo and in
tests/msh.rs. The tests check that both files read into the same mesh.

Needs Gmsh from PyPI (`pip install gmsh`; on Debian also
`apt-get install libglu1-mesa libxcursor1 libxft2 libxinerama1 libgl1 libgomp1`).
The tests only read the committed .msh; Gmsh is not needed to run them.
"""

import os

import gmsh

here = os.path.dirname(os.path.abspath(__file__))
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.open(os.path.join(here, "gmsh_two_volumes.geo"))
gmsh.model.mesh.generate(3)
gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
gmsh.option.setNumber("Mesh.SaveAll", 0)  # only elements of physical groups
gmsh.option.setNumber("Mesh.Binary", 0)
gmsh.write(os.path.join(here, "gmsh_two_volumes.msh"))
gmsh.option.setNumber("Mesh.Binary", 1)
gmsh.write(os.path.join(here, "gmsh_two_volumes_binary.msh"))
gmsh.option.setNumber("Mesh.Binary", 0)

print("gmsh", gmsh.__version__)
tags, xyz, _ = gmsh.model.mesh.getNodes()
print("nodes", len(tags))
pos = {int(t): xyz[3 * i : 3 * i + 3] for i, t in enumerate(tags)}


def signed_volume(a, b, c, d):
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    w = [d[k] - a[k] for k in range(3)]
    return (
        u[0] * (v[1] * w[2] - v[2] * w[1])
        - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0])
    ) / 6.0


for dim, ptag in gmsh.model.getPhysicalGroups():
    name = gmsh.model.getPhysicalName(dim, ptag)
    counts = {}
    for ent in gmsh.model.getEntitiesForPhysicalGroup(dim, ptag):
        types, etags, _ = gmsh.model.mesh.getElements(dim, ent)
        for t, e in zip(types, etags):
            counts[int(t)] = counts.get(int(t), 0) + len(e)
    print(f"physical dim {dim} tag {ptag} {name!r}: elements by type {counts}")
    if dim == 3:
        vols = []
        for ent in gmsh.model.getEntitiesForPhysicalGroup(dim, ptag):
            _, ntags = gmsh.model.mesh.getElementsByType(4, ent)
            for i in range(0, len(ntags), 4):
                vols.append(signed_volume(*(pos[int(n)] for n in ntags[i : i + 4])))
        print(f"  volume {sum(abs(v) for v in vols)!r} m^3, negative tets {sum(v < 0 for v in vols)}")
gmsh.finalize()
