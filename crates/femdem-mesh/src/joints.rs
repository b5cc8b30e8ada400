//! Insertion of 6-node cohesive joint elements (reference paper §2.1, Fig. 2).
//!
//! Every tet of a breakable region gets its own four nodes; each interior
//! face between two tets that are not both unbreakable gets one joint
//! `N1 N2 N3 – N4 N5 N6`:
//!
//! * `N1 N2 N3` are the nodes of the first tet (`a`, the lower tet index) on
//!   that face, counter-clockwise seen from outside `a`, so
//!   `(N2 − N1) × (N3 − N1)` points from `a` towards `b`;
//! * `N4 N5 N6` are the nodes of the second tet (`b`) that start at the same
//!   positions as `N3 N2 N1`: `N1–N6`, `N2–N5`, `N3–N4` coincide, the pairs
//!   whose midpoints `N16`, `N25`, `N34` span the joint's local x′y′ plane.
//!   `N4 N5 N6` is thus counter-clockwise seen from outside `b`.
//!
//! Every node keeps the id of the original vertex it was split from
//! ([`JointedMesh::origin`]): "sharing a node" in the sense of Eq. 15 means
//! having the same origin. Tets of unbreakable regions keep shared nodes as
//! in ordinary FEM; a face between an unbreakable and a breakable tet is
//! jointed like any other (the unbreakable side's nodes are shared with its
//! unbreakable neighbours). Faces listed in [`TetMesh::fracture_faces`]
//! (pre-existing fractures) get no joint and are returned as initial
//! contact face pairs instead.
//!
//! [`insert_joints_within`] confines the joints of breakable regions to a
//! *joint zone*, a per-tet mask: a tet of a breakable region outside the
//! zone keeps shared nodes like an unbreakable one (the rest of the region
//! is a plain elastic continuum), and a face on the zone's edge, between a
//! tet inside and one outside, is jointed like a face between a breakable
//! and an unbreakable tet. How the mask is drawn (boxes, spheres, …) is the
//! caller's business.

use std::collections::HashSet;

use femdem_core::tet::FACES;

use crate::faces::{face_adjacency, face_key};
use crate::{FaceRef, MeshError, TetMesh};

/// A mesh with joints inserted.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct JointedMesh {
    /// The mesh on the split nodes. Tet indices, regions, boundary groups
    /// and fracture faces are those of the input mesh.
    pub mesh: TetMesh,
    /// For each node, the vertex of the input mesh it was split from.
    pub origin: Vec<u32>,
    /// Joint connectivity `[N1, N2, N3, N4, N5, N6]` (see the module doc).
    pub joints: Vec<[u32; 6]>,
    /// For each joint, the face of tet `a` (carrying `N1 N2 N3`) and the face
    /// of tet `b` (carrying `N4 N5 N6`).
    pub joint_faces: Vec<(FaceRef, FaceRef)>,
    /// Face pairs on pre-existing fractures: no joint, in contact from the
    /// start.
    pub initial_contacts: Vec<(FaceRef, FaceRef)>,
    /// How many of the joints lie between a tet that owns its nodes and one
    /// that shares them: a breakable and an unbreakable tet, or a tet inside
    /// and one outside the joint zone of [`insert_joints_within`].
    pub interface_joints: usize,
}

impl JointedMesh {
    /// Bytes held by the arrays (capacity is not counted).
    pub fn array_bytes(&self) -> usize {
        use std::mem::size_of;
        self.mesh.array_bytes()
            + self.origin.len() * size_of::<u32>()
            + self.joints.len() * size_of::<[u32; 6]>()
            + (self.joint_faces.len() + self.initial_contacts.len()) * size_of::<(FaceRef, FaceRef)>()
    }
}

/// Splits the nodes of breakable regions and inserts the joints.
///
/// # Errors
/// [`MeshError::NonManifoldFace`] from the face adjacency, and
/// [`MeshError::BadFractureFace`] for a fracture face that is not interior
/// or lies between two unbreakable tets.
pub fn insert_joints(mesh: &TetMesh) -> Result<JointedMesh, MeshError> {
    insert(mesh, |_| true)
}

/// Like [`insert_joints`], with the joints confined to the tets `zone`
/// marks: tet `t` owns its nodes when its region is breakable *and*
/// `zone[t]`; every other tet shares its nodes with its unsplit neighbours.
/// A joint sits on each interior face with at least one split tet, so the
/// zone's edge is jointed on its inside (counted in
/// [`JointedMesh::interface_joints`]). With `zone` all true this is
/// [`insert_joints`].
///
/// # Errors
/// As [`insert_joints`] (a fracture face between two unsplit tets of a
/// breakable region is refused: its shared nodes could never part), and
/// [`MeshError::Inconsistent`] when `zone` does not have one entry per tet.
pub fn insert_joints_within(mesh: &TetMesh, zone: &[bool]) -> Result<JointedMesh, MeshError> {
    if zone.len() != mesh.tets.len() {
        return Err(MeshError::Inconsistent(format!(
            "the joint zone has {} entries for {} tets",
            zone.len(),
            mesh.tets.len()
        )));
    }
    insert(mesh, |t| zone[t as usize])
}

/// Joint insertion where a tet of a breakable region is split only if
/// `in_zone(t)`.
fn insert(mesh: &TetMesh, in_zone: impl Fn(u32) -> bool) -> Result<JointedMesh, MeshError> {
    let breakable: Vec<bool> = mesh.regions.iter().map(|r| r.breakable).collect();
    let region_breakable = |t: u32| breakable[mesh.tet_region[t as usize] as usize];
    let is_breakable = |t: u32| region_breakable(t) && in_zone(t);

    // 1. Nodes: four fresh ones per breakable tet, shared ones otherwise.
    let mut coords = Vec::with_capacity(mesh.tets.len() * 4);
    let mut origin = Vec::with_capacity(mesh.tets.len() * 4);
    let mut shared = vec![u32::MAX; mesh.coords.len()];
    let mut tets = Vec::with_capacity(mesh.tets.len());
    for (t, tet) in mesh.tets.iter().enumerate() {
        let split = is_breakable(t as u32);
        tets.push(tet.map(|v| {
            if !split && shared[v as usize] != u32::MAX {
                return shared[v as usize];
            }
            let n = coords.len() as u32;
            coords.push(mesh.coords[v as usize]);
            origin.push(v);
            if !split {
                shared[v as usize] = n;
            }
            n
        }));
    }
    drop(shared);

    // 2. Joints on interior faces.
    let fracture: HashSet<u128> = mesh.fracture_faces.iter().map(|f| face_key(f.nodes(&mesh.tets))).collect();
    let adjacency = face_adjacency(mesh)?;
    let mut out = JointedMesh::default();
    let mut matched_fractures = 0usize;
    for &(fa, fb) in &adjacency.interior {
        let (ba, bb) = (is_breakable(fa.tet), is_breakable(fb.tet));
        let on_fracture = !fracture.is_empty() && fracture.contains(&face_key(fa.nodes(&mesh.tets)));
        if on_fracture {
            if !ba && !bb {
                let reason = if region_breakable(fa.tet) || region_breakable(fb.tet) {
                    "lies between two tets outside the joint zone, whose shared nodes cannot separate"
                } else {
                    "lies between two unbreakable tets, whose shared nodes cannot separate"
                };
                return Err(MeshError::BadFractureFace { tet: fa.tet, local: fa.local, reason });
            }
            matched_fractures += 1;
            out.initial_contacts.push((fa, fb));
            continue;
        }
        if !ba && !bb {
            continue;
        }
        if ba != bb {
            out.interface_joints += 1;
        }
        out.joints.push(joint_nodes(mesh, &tets, fa, fb));
        out.joint_faces.push((fa, fb));
    }
    if matched_fractures != fracture.len() {
        let bad = mesh
            .fracture_faces
            .iter()
            .find(|f| {
                let k = face_key(f.nodes(&mesh.tets));
                !out.initial_contacts.iter().any(|(a, _)| face_key(a.nodes(&mesh.tets)) == k)
            })
            .copied()
            .unwrap_or(FaceRef { tet: 0, local: 0 });
        return Err(MeshError::BadFractureFace {
            tet: bad.tet,
            local: bad.local,
            reason: "is not shared by two tets (a fracture face must be interior)",
        });
    }
    out.mesh = TetMesh { coords, tets, ..mesh.clone_without_geometry() };
    out.origin = origin;
    Ok(out)
}

/// `[N1..N6]` for the face shared by `fa` (tet a) and `fb` (tet b).
fn joint_nodes(mesh: &TetMesh, new_tets: &[[u32; 4]], fa: FaceRef, fb: FaceRef) -> [u32; 6] {
    let (a, b) = (fa.tet as usize, fb.tet as usize);
    let local_a = FACES[fa.local as usize];
    let n_a = local_a.map(|i| new_tets[a][i]);
    let v_a = local_a.map(|i| mesh.tets[a][i]);
    let on_b = |v: u32| {
        let i = mesh.tets[b].iter().position(|&w| w == v).expect("shared face vertex is in both tets");
        new_tets[b][i]
    };
    [n_a[0], n_a[1], n_a[2], on_b(v_a[2]), on_b(v_a[1]), on_b(v_a[0])]
}

impl TetMesh {
    /// A copy of everything but the node coordinates and the connectivity.
    fn clone_without_geometry(&self) -> TetMesh {
        TetMesh {
            coords: Vec::new(),
            tets: Vec::new(),
            tet_region: self.tet_region.clone(),
            regions: self.regions.clone(),
            boundary: self.boundary.clone(),
            fracture_faces: self.fracture_faces.clone(),
        }
    }
}
