// Fixture for crates/femdem-mesh/tests/msh.rs: a 10 mm cube of "matrix"
// with a cylindrical "inclusion" (radius 2.5 mm, height 6 mm, axis along z
// through the cube's centre), meshed coarsely with linear tets.
//
// Regenerate with `python regenerate.py` (Gmsh from PyPI, `pip install
// gmsh`); the counts it prints are asserted by the test. Measured with
// Gmsh 4.15.2 through its Python API (see regenerate.py):
//   nodes 116
//   physical volume 1 "matrix":    335 tets (type 4), volume 8.925346089639112e-07 m^3
//   physical volume 2 "inclusion":  68 tets (type 4), volume 1.074653910360876e-07 m^3
//     (faceted; the true cylinder holds pi R^2 H = 1.1780972450961724e-07 m^3)
//   physical surface 1 "bottom":              26 triangles (type 2)
//   physical surface 2 "top":                 26 triangles (type 2)
//   physical surface 3 "inclusion_boundary":  66 triangles (type 2), interior
//   physical curve 1 "z_axis_edge":            3 lines (type 1)
//   physical point 1 "origin":                 1 point (type 15)
//   no tet has negative orientation
SetFactory("OpenCASCADE");

L = 0.01;    // cube edge, m
R = 0.0025;  // inclusion radius, m
H = 0.006;   // inclusion height, m
Z0 = 0.002;  // inclusion bottom, m

Box(1) = {0, 0, 0, L, L, L};
Cylinder(2) = {L / 2, L / 2, Z0, 0, 0, H, R};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }

e = 1e-6;
inc() = Volume In BoundingBox{L/2 - R - e, L/2 - R - e, Z0 - e, L/2 + R + e, L/2 + R + e, Z0 + H + e};
mat() = Volume{:};
mat() -= inc();

Physical Volume("matrix", 1) = {mat()};
Physical Volume("inclusion", 2) = {inc()};

Physical Surface("bottom", 1) = Surface In BoundingBox{-e, -e, -e, L + e, L + e, e};
Physical Surface("top", 2) = Surface In BoundingBox{-e, -e, L - e, L + e, L + e, L + e};
// An interior surface: its triangles are shared by a matrix and an
// inclusion tet.
Physical Surface("inclusion_boundary", 3) = Surface In BoundingBox{L/2 - R - e, L/2 - R - e, Z0 - e, L/2 + R + e, L/2 + R + e, Z0 + H + e};

// Lower-dimensional groups, so the file also holds line (type 1) and point
// (type 15) elements, which the femdem reader skips and counts.
Physical Curve("z_axis_edge", 1) = Curve In BoundingBox{-e, -e, -e, e, e, L + e};
Physical Point("origin", 1) = Point In BoundingBox{-e, -e, -e, e, e, e};

// Coarse on purpose: a few hundred tets keep the file small (~17 kB).
MeshSize{ PointsOf{ Volume{:}; } } = 0.004;
Mesh.ElementOrder = 1;
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
