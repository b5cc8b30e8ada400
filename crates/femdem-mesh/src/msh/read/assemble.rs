//! The last stage of reading an MSH file: the mesh assembled from the
//! records read — nodes that tets use (coincident ones refused), tets
//! oriented, regions from physical volumes, boundary groups from physical
//! surfaces matched to tet faces.

use std::collections::{BTreeSet, HashMap};

use femdem_core::tet::signed_volume;

use super::super::report::MshReport;
use super::super::source::{At, Source};
use super::{ANY_DIMENSION, Reader, UNNAMED};
use crate::faces::{face_key, sorted_face_keys};
use crate::{BoundaryGroup, FaceRef, MeshError, Region, TetMesh};

impl<'a, S: Source<'a>> Reader<S> {
    /// Builds the mesh from what was read.
    pub(super) fn assemble(mut self) -> Result<(TetMesh, MshReport), MeshError> {
        let elements_at = self.elements_at.unwrap_or(At::Line(1));
        let err_elements = |message: String| elements_at.err("Elements", message);
        if self.tets.is_empty() {
            let mut message = String::from("no 4-node tetrahedra (element type 4) in the file");
            if !self.report.skipped_elements.is_empty() {
                message.push_str(&format!(
                    " ({}); femdem needs linear tets (in Gmsh, `Mesh.ElementOrder = 1` \
                     and no recombination)",
                    self.report
                ));
            }
            return Err(err_elements(message));
        }

        // Keep the nodes that tets use, in file order.
        let mut used = vec![false; self.coords.len()];
        for t in &self.tets {
            for &v in t {
                used[v as usize] = true;
            }
        }
        let mut new_index = vec![u32::MAX; self.coords.len()];
        let mut coords = Vec::with_capacity(self.coords.len());
        for (i, c) in self.coords.iter().enumerate() {
            if used[i] {
                new_index[i] = coords.len() as u32;
                coords.push(*c);
            }
        }
        self.report.dropped_nodes = self.coords.len() - coords.len();
        self.refuse_coincident_nodes(&used)?;
        let mut mesh = TetMesh { coords, ..Default::default() };
        mesh.tets = self.tets.iter().map(|t| t.map(|v| new_index[v as usize])).collect();
        for t in 0..mesh.tets.len() {
            if signed_volume(&mesh.tet_points(t)) < 0.0 {
                mesh.tets[t].swap(2, 3);
                self.report.reoriented_tets += 1;
            }
        }

        // Regions: physical volumes by tag, then "unnamed".
        let volumes = self.volumes.take().unwrap_or_default();
        let phys_volumes: BTreeSet<i32> = volumes.values().flatten().copied().collect();
        let mut region_of: HashMap<Option<i32>, u16> = HashMap::new();
        let add_region = |regions: &mut Vec<Region>, name: String| -> Result<u16, MeshError> {
            if let Some(i) = regions.iter().position(|r| r.name == name) {
                return Ok(i as u16);
            }
            let i = u16::try_from(regions.len())
                .map_err(|_| err_elements("more than 65536 regions (physical volumes)".into()))?;
            regions.push(Region { name, breakable: true });
            Ok(i)
        };
        for &p in &phys_volumes {
            let name = self.name(3, p).unwrap_or_else(|| format!("volume_{p}"));
            region_of.insert(Some(p), add_region(&mut mesh.regions, name)?);
        }
        if self.tet_phys.iter().any(Option::is_none) {
            region_of.insert(None, add_region(&mut mesh.regions, UNNAMED.to_owned())?);
        }
        mesh.tet_region = self.tet_phys.iter().map(|p| region_of[p]).collect();

        // Boundary groups: physical surfaces by tag.
        let phys_surfaces: BTreeSet<i32> = self.surfaces.values().flatten().copied().collect();
        let mut group_of: HashMap<i32, usize> = HashMap::new();
        for &p in &phys_surfaces {
            let name = self.name(2, p).unwrap_or_else(|| format!("surface_{p}"));
            let g = match mesh.boundary.iter().position(|g| g.name == name) {
                Some(g) => g,
                None => {
                    mesh.boundary.push(BoundaryGroup { name, faces: Vec::new() });
                    mesh.boundary.len() - 1
                }
            };
            group_of.insert(p, g);
        }
        let keys = sorted_face_keys(&mesh);
        for tri in &self.triangles {
            let nodes = tri.nodes.map(|v| new_index[v as usize]);
            let face = match_face(&mesh, &keys, nodes).ok_or_else(|| {
                tri.at.err("Elements", format!("triangle on surface {} is not a face of any tet", tri.entity))
            })?;
            for p in self.surfaces.get(&tri.entity).into_iter().flatten() {
                if let Some(&g) = group_of.get(p) {
                    mesh.boundary[g].faces.push(face);
                }
            }
        }
        Ok((mesh, self.report))
    }

    /// The name of physical group `tag` of dimension `dim`, if
    /// `$PhysicalNames` gives one (MSH 2.0's names have no dimension).
    fn name(&self, dim: i32, tag: i32) -> Option<String> {
        self.names.get(&(dim, tag)).or_else(|| self.names.get(&(ANY_DIMENSION, tag))).cloned()
    }

    /// Refuses two nodes that tets use at one point: they would split the
    /// tets that use them with no joint between them (a hidden crack that
    /// nothing holds and contact does not see). The error names both places.
    fn refuse_coincident_nodes(&self, used: &[bool]) -> Result<(), MeshError> {
        let mut order: Vec<usize> = (0..self.coords.len()).filter(|&i| used[i]).collect();
        let key = |i: &usize| self.coords[*i];
        order.sort_by(|a, b| {
            let (p, q) = (key(a), key(b));
            p[0].total_cmp(&q[0]).then(p[1].total_cmp(&q[1])).then(p[2].total_cmp(&q[2])).then(a.cmp(b))
        });
        if let Some(w) = order.windows(2).find(|w| self.coords[w[0]] == self.coords[w[1]]) {
            let (first, second) = (w[0].min(w[1]), w[0].max(w[1]));
            let c = self.coords[second];
            return Err(self.coord_at[second].err(
                "Nodes",
                format!(
                    "the node at ({}, {}, {}) coincides with the node on {}: two nodes at one point would \
                     split the tets that use them with no joint between them (a hidden crack that nothing holds \
                     and contact does not see); merge them (in Gmsh, `Coherence;`) or model the fracture \
                     another way",
                    c[0],
                    c[1],
                    c[2],
                    self.coord_at[first].describe()
                ),
            ));
        }
        Ok(())
    }
}

/// The tet face with the same nodes as the triangle `nodes`; of two (an
/// interior face), the one whose outward order is a rotation of `nodes`.
fn match_face(mesh: &TetMesh, keys: &[(u128, u32)], nodes: [u32; 3]) -> Option<FaceRef> {
    if nodes.contains(&u32::MAX) {
        return None; // a node no tet uses
    }
    let key = face_key(nodes);
    let first = keys.partition_point(|&(k, _)| k < key);
    let candidates = keys[first..].iter().take_while(|&&(k, _)| k == key);
    let mut found = None;
    for &(_, slot) in candidates {
        let f = FaceRef { tet: slot / 4, local: (slot % 4) as u8 };
        let o = f.nodes(&mesh.tets);
        let same_turn = (0..3).any(|r| o[r] == nodes[0] && o[(r + 1) % 3] == nodes[1]);
        if same_turn {
            return Some(f);
        }
        found.get_or_insert(f);
    }
    found
}
