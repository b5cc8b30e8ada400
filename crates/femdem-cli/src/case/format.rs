//! The TOML case format, version 1, as serde structs. Every table rejects
//! unknown keys. Units are SI (metres, seconds, pascals, kilograms).
//! The annotated reference is `docs/case-format.md`.

use serde::Deserialize;
use toml::Spanned;

/// The case format version this build reads.
pub const CASE_VERSION: u32 = 1;

/// A whole case file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Case {
    /// Format version; must equal [`CASE_VERSION`].
    pub version: Spanned<u32>,
    /// Free text shown in reports.
    #[serde(default)]
    pub title: String,
    /// How the mesh is made.
    pub mesh: MeshSection,
}

/// `[mesh]`: regions, parts and the seed of random generators.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSection {
    /// Seed for every random choice of the generators (default 0).
    #[serde(default)]
    pub seed: u64,
    /// `[[mesh.regions]]`: every region a part or an MSH file uses.
    pub regions: Vec<Spanned<RegionSpec>>,
    /// `[[mesh.parts]]`: bodies, meshed in order and never sharing nodes.
    pub parts: Vec<Spanned<PartSpec>>,
}

/// `[[mesh.regions]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RegionSpec {
    /// Region name, referred to by parts and by MSH physical volume names.
    pub name: String,
    /// Whether joints are inserted so the region can fracture.
    pub breakable: bool,
}

/// `[[mesh.parts]]`, told apart by `kind`.
#[derive(Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum PartSpec {
    /// `kind = "box"`: a jittered lattice box.
    Box {
        /// Part name (default: the region name); prefixes its boundary groups.
        name: Option<String>,
        /// Region of its tets.
        region: String,
        /// Lower corner, m.
        min: [f64; 3],
        /// Upper corner, m.
        max: [f64; 3],
        /// Target element size, m.
        element_size: f64,
        /// Random vertex offset as a fraction of the element size (default 0.1).
        jitter: Option<f64>,
    },
    /// `kind = "extrusion"`: a 2D outline extruded along z.
    Extrusion {
        /// Part name (default: the region name).
        name: Option<String>,
        /// Region of its tets.
        region: String,
        /// Circular outline (exclusive with `polygon`).
        circle: Option<CircleSpec>,
        /// Polygonal outline (exclusive with `circle`).
        polygon: Option<Vec<[f64; 2]>>,
        /// Pre-existing fracture traces: polylines inside the outline.
        #[serde(default)]
        traces: Vec<Vec<[f64; 2]>>,
        /// Bottom z, m (default 0).
        #[serde(default)]
        z0: f64,
        /// Extrusion height, m.
        thickness: f64,
        /// Target element size, m.
        element_size: f64,
        /// Number of layers (default: thickness / element_size, rounded).
        layers: Option<usize>,
    },
    /// `kind = "platen"`: a rigid loading platen against the parts before it.
    Platen {
        /// Part name (default: the region name).
        name: Option<String>,
        /// Region of its tets.
        region: String,
        /// Side of the specimen: `"+x"`, `"-x"`, `"+y"`, `"-y"`, `"+z"`, `"-z"`.
        side: String,
        /// Thickness along the side's normal, m.
        thickness: f64,
        /// Extent along the two other axes in axis order, m (default: the
        /// specimen's extent).
        extent: Option<[f64; 2]>,
        /// Target element size, m.
        element_size: f64,
    },
    /// `kind = "msh"`: a Gmsh MSH 4.1 ASCII file.
    Msh {
        /// Part name (default: the file stem).
        name: Option<String>,
        /// Path, relative to the case file.
        path: String,
    },
}

/// `circle = { center = [x, y], radius = r }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CircleSpec {
    /// Centre, m.
    pub center: [f64; 2],
    /// Radius, m.
    pub radius: f64,
}
