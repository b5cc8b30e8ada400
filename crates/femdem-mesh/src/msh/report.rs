//! What the MSH reader reports besides the mesh, and the Gmsh element
//! types it knows.

use std::collections::BTreeMap;
use std::fmt;

/// What [`read_msh_report`](super::read_msh_report) left out of the mesh or changed in it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MshReport {
    /// Elements that are neither 4-node tets nor 3-node triangles, counted
    /// by Gmsh element type number (see [`element_type_name`]).
    pub skipped_elements: BTreeMap<u32, usize>,
    /// Triangles on surfaces in no physical group: they name no boundary
    /// group, so they are not kept.
    pub ungrouped_triangles: usize,
    /// Nodes used by no tet, dropped from the mesh.
    pub dropped_nodes: usize,
    /// Tets given in negative orientation, reoriented by swapping their
    /// last two nodes.
    pub reoriented_tets: usize,
}

impl MshReport {
    /// The skipped elements that are, or may be, volume elements — of
    /// dimension 3 or of a type [`element_type_name`] does not know — by
    /// type: where a mesh holds them beside its tets, part of the body is
    /// missing from what was read.
    pub fn skipped_volumes(&self) -> BTreeMap<u32, usize> {
        self.skipped_elements
            .iter()
            .filter(|&(&ty, _)| element_type_dimension(ty).is_none_or(|d| d == 3))
            .map(|(&ty, &n)| (ty, n))
            .collect()
    }
}

impl fmt::Display for MshReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut parts = Vec::new();
        if !self.skipped_elements.is_empty() {
            let skipped: Vec<String> = self
                .skipped_elements
                .iter()
                .map(|(&ty, &n)| match element_type_name(ty) {
                    Some(name) => format!("{n} {name} (type {ty})"),
                    None => format!("{n} of type {ty}"),
                })
                .collect();
            parts.push(format!("skipped elements: {}", skipped.join(", ")));
        }
        if self.ungrouped_triangles > 0 {
            parts.push(format!("{} triangle(s) in no physical surface ignored", self.ungrouped_triangles));
        }
        if self.dropped_nodes > 0 {
            parts.push(format!("{} node(s) used by no tet dropped", self.dropped_nodes));
        }
        if self.reoriented_tets > 0 {
            parts.push(format!("{} tet(s) reoriented", self.reoriented_tets));
        }
        if parts.is_empty() { f.write_str("nothing skipped") } else { f.write_str(&parts.join("; ")) }
    }
}

/// Gmsh element types known by name, with their node counts and
/// dimensions.
const ELEMENT_TYPES: [(u32, &str, usize, u8); 19] = [
    (1, "2-node line", 2, 1),
    (2, "3-node triangle", 3, 2),
    (3, "4-node quadrangle", 4, 2),
    (4, "4-node tetrahedron", 4, 3),
    (5, "8-node hexahedron", 8, 3),
    (6, "6-node prism", 6, 3),
    (7, "5-node pyramid", 5, 3),
    (8, "3-node line", 3, 1),
    (9, "6-node triangle", 6, 2),
    (10, "9-node quadrangle", 9, 2),
    (11, "10-node tetrahedron", 10, 3),
    (12, "27-node hexahedron", 27, 3),
    (13, "18-node prism", 18, 3),
    (14, "14-node pyramid", 14, 3),
    (15, "point", 1, 0),
    (16, "8-node quadrangle", 8, 2),
    (17, "20-node hexahedron", 20, 3),
    (18, "15-node prism", 15, 3),
    (19, "13-node pyramid", 13, 3),
];

/// The Gmsh name of element type `ty` (e.g. `"2-node line"` for 1), for the
/// common first- and second-order types; `None` for others.
pub fn element_type_name(ty: u32) -> Option<&'static str> {
    ELEMENT_TYPES.iter().find(|e| e.0 == ty).map(|e| e.1)
}

/// The dimension of element type `ty` (0 a point, … 3 a volume), for the
/// types [`element_type_name`] knows; `None` for others.
pub fn element_type_dimension(ty: u32) -> Option<u8> {
    ELEMENT_TYPES.iter().find(|e| e.0 == ty).map(|e| e.3)
}

pub(super) fn element_type_nodes(ty: u32) -> Option<usize> {
    ELEMENT_TYPES.iter().find(|e| e.0 == ty).map(|e| e.2)
}
