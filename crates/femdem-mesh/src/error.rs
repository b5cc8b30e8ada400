//! Errors of the mesh crate.

use thiserror::Error;

/// Everything that can go wrong while building, reading or checking a mesh.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum MeshError {
    /// A generator parameter is out of range.
    #[error("invalid generator parameter `{name}`: {reason}")]
    InvalidParameter {
        /// Parameter name as it appears in a case file.
        name: &'static str,
        /// Why it was rejected.
        reason: String,
    },
    /// The 2D triangulation failed (e.g. a self-intersecting outline).
    #[error("2D triangulation failed: {0}")]
    Triangulation(String),
    /// Features of an extrusion's outline and traces that come too close
    /// to each other to be meshed (see `generate::closest_approach`).
    #[error("{0}")]
    Clearance(String),
    /// A malformed Gmsh MSH file: an ASCII one, or the text head of a
    /// binary one (up to the file type in `$MeshFormat`).
    #[error("MSH line {line}: {message}")]
    Msh {
        /// 1-based line number in the file.
        line: usize,
        /// What is wrong there.
        message: String,
    },
    /// A malformed binary Gmsh MSH file, past its `$MeshFormat` line.
    #[error("MSH binary file, byte {offset}{}: {message}", in_section(.section))]
    MshBinary {
        /// 0-based byte offset in the file of the first problem: the value
        /// that is wrong, or where the file ends too soon.
        offset: usize,
        /// The section it is in (`"Nodes"` for `$Nodes`), empty between
        /// sections.
        section: String,
        /// What is wrong there.
        message: String,
    },
    /// A tet with negative or (near) zero volume.
    #[error("tet {tet} is {kind} (volume {volume:.3e} m³)")]
    BadTet {
        /// Tet index.
        tet: usize,
        /// `"inverted"` or `"degenerate"`.
        kind: &'static str,
        /// Its signed volume.
        volume: f64,
    },
    /// A tet refers to a node that does not exist.
    #[error("tet {tet} refers to node {node}, but the mesh has {num_nodes} nodes")]
    NodeOutOfRange {
        /// Tet index.
        tet: usize,
        /// The bad node id.
        node: u32,
        /// Number of nodes in the mesh.
        num_nodes: usize,
    },
    /// Nodes that no tet uses.
    #[error("{count} node(s) are used by no tet (first: node {first})")]
    UnreferencedNodes {
        /// How many.
        count: usize,
        /// The first one.
        first: u32,
    },
    /// A face shared by more than two tets (non-manifold mesh).
    #[error("face with nodes {nodes:?} is shared by {count} tets (at most 2 allowed)")]
    NonManifoldFace {
        /// The face's node ids, sorted.
        nodes: [u32; 3],
        /// How many tets share it.
        count: usize,
    },
    /// Two tets on the same side of the face they share: the mesh is
    /// tangled (an element inverted by a misplaced node, or two elements
    /// overlapping), which orientation alone does not show once each tet's
    /// node order is made positive.
    #[error(
        "tets {a} and {b} lie on the same side of the face they share (nodes {nodes:?}): the mesh is tangled \
         (a node moved through a face, or elements overlapping)"
    )]
    TangledFace {
        /// The lower tet index.
        a: usize,
        /// The other tet.
        b: usize,
        /// The face's node ids, sorted.
        nodes: [u32; 3],
    },
    /// A pre-existing fracture face that cannot be honoured.
    #[error("fracture face of tet {tet} (local face {local}) {reason}")]
    BadFractureFace {
        /// Tet index.
        tet: u32,
        /// Local face index.
        local: u8,
        /// Why.
        reason: &'static str,
    },
    /// A fracture trace of an extrusion that cannot be meshed: it leaves the
    /// outline, repeats a point, overlaps another trace, ...
    #[error("trace {trace}, point {point}: {reason}")]
    Trace {
        /// Index of the trace (0-based, in the order given).
        trace: usize,
        /// Index of the point of that trace where the problem is (0-based).
        point: usize,
        /// What is wrong there.
        reason: String,
    },
    /// Arrays of the mesh that disagree with each other.
    #[error("inconsistent mesh: {0}")]
    Inconsistent(String),
}

/// `" in $Nodes"` for `"Nodes"`, nothing for no section.
fn in_section(section: &str) -> String {
    if section.is_empty() { String::new() } else { format!(" in ${section}") }
}
