//! The tetrahedral mesh type, held as flat parallel arrays.

use femdem_core::{Real, Vec3};

/// A region: a named set of tets sharing a material and a fracture setting.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Region {
    /// Name used by case files and output (e.g. `"disc"`, `"platen_top"`).
    pub name: String,
    /// Whether joints (cohesive elements) are inserted in this region, so it
    /// may fracture. Unbreakable regions stay ordinary continuous FEM with
    /// shared nodes: a scene pays for joints only where fracture can happen.
    pub breakable: bool,
}

/// One face of one tet: face `local` is the face opposite local node `local`,
/// with the outward ordering of [`femdem_core::tet::FACES`].
///
/// Faces are named by tet and local index, not by vertex ids, so that they
/// stay valid when joint insertion renumbers the nodes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct FaceRef {
    /// Tet index.
    pub tet: u32,
    /// Local face index, 0..4.
    pub local: u8,
}

impl FaceRef {
    /// The face's three node ids in outward order.
    pub fn nodes(self, tets: &[[u32; 4]]) -> [u32; 3] {
        let t = tets[self.tet as usize];
        femdem_core::tet::FACES[self.local as usize].map(|i| t[i])
    }
}

/// A named group of boundary faces, used by loads and constraints.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BoundaryGroup {
    /// Group name (e.g. `"top"`, `"xmin"`, a Gmsh physical surface name).
    pub name: String,
    /// The faces, each named from the tet that owns it.
    pub faces: Vec<FaceRef>,
}

/// A tetrahedral mesh in structure-of-arrays form. Units: metres.
///
/// Invariants checked by [`crate::check::check`]: every tet has positive
/// volume, every node is used, no face is shared by more than two tets, and
/// the two tets that share a face lie on its two sides (no tangle).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TetMesh {
    /// Node coordinates.
    pub coords: Vec<[Real; 3]>,
    /// Tet connectivity, four node ids per tet, positive orientation
    /// (see [`femdem_core::tet`]).
    pub tets: Vec<[u32; 4]>,
    /// Region index of each tet, into [`TetMesh::regions`].
    pub tet_region: Vec<u16>,
    /// The regions.
    pub regions: Vec<Region>,
    /// Named boundary-face groups.
    pub boundary: Vec<BoundaryGroup>,
    /// Interior faces lying on pre-existing fractures (one side of each):
    /// joint insertion puts no joint there and lists them as initial contact.
    pub fracture_faces: Vec<FaceRef>,
}

impl TetMesh {
    /// Number of nodes.
    pub fn num_nodes(&self) -> usize {
        self.coords.len()
    }

    /// Number of tets.
    pub fn num_tets(&self) -> usize {
        self.tets.len()
    }

    /// Position of node `i`.
    #[inline]
    pub fn point(&self, i: u32) -> Vec3 {
        let c = self.coords[i as usize];
        Vec3::new(c[0], c[1], c[2])
    }

    /// The four corner positions of tet `t`.
    #[inline]
    pub fn tet_points(&self, t: usize) -> [Vec3; 4] {
        self.tets[t].map(|n| self.point(n))
    }

    /// Index of the region called `name`.
    pub fn region_index(&self, name: &str) -> Option<u16> {
        self.regions.iter().position(|r| r.name == name).map(|i| i as u16)
    }

    /// The boundary group called `name`.
    pub fn boundary_group(&self, name: &str) -> Option<&BoundaryGroup> {
        self.boundary.iter().find(|g| g.name == name)
    }

    /// Bytes held by the arrays (capacity is not counted).
    pub fn array_bytes(&self) -> usize {
        use std::mem::size_of;
        self.coords.len() * size_of::<[Real; 3]>()
            + self.tets.len() * size_of::<[u32; 4]>()
            + self.tet_region.len() * size_of::<u16>()
            + self.boundary.iter().map(|g| g.faces.len() * size_of::<FaceRef>()).sum::<usize>()
            + self.fracture_faces.len() * size_of::<FaceRef>()
    }

    /// Appends `other` as a separate body: its nodes are renumbered after
    /// ours and never merged with them. Regions are merged by name (the
    /// breakable flag of an existing region wins); boundary groups with the
    /// same name are concatenated.
    pub fn append(&mut self, other: &TetMesh) {
        let node_offset = self.coords.len() as u32;
        let tet_offset = self.tets.len() as u32;
        let region_map: Vec<u16> = other
            .regions
            .iter()
            .map(|r| match self.region_index(&r.name) {
                Some(i) => i,
                None => {
                    self.regions.push(r.clone());
                    (self.regions.len() - 1) as u16
                }
            })
            .collect();
        self.coords.extend_from_slice(&other.coords);
        self.tets.extend(other.tets.iter().map(|t| t.map(|n| n + node_offset)));
        self.tet_region.extend(other.tet_region.iter().map(|&r| region_map[r as usize]));
        let shift = |f: &FaceRef| FaceRef { tet: f.tet + tet_offset, local: f.local };
        for g in &other.boundary {
            let faces = g.faces.iter().map(shift);
            match self.boundary.iter_mut().find(|h| h.name == g.name) {
                Some(h) => h.faces.extend(faces),
                None => self.boundary.push(BoundaryGroup { name: g.name.clone(), faces: faces.collect() }),
            }
        }
        self.fracture_faces.extend(other.fracture_faces.iter().map(shift));
    }

    /// Axis-aligned bounding box `(min, max)`; `None` for an empty mesh.
    pub fn bounding_box(&self) -> Option<([Real; 3], [Real; 3])> {
        let first = *self.coords.first()?;
        Some(self.coords.iter().fold((first, first), |(mut lo, mut hi), c| {
            for k in 0..3 {
                lo[k] = lo[k].min(c[k]);
                hi[k] = hi[k].max(c[k]);
            }
            (lo, hi)
        }))
    }
}
