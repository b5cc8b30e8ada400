//! Rigid loading platens: boxes placed against a side of a specimen as
//! separate bodies (they share no node with the specimen).

use super::{BoxSpec, generate_box, positive};
use crate::{MeshError, Region, TetMesh};

/// A side of an axis-aligned bounding box.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// The side at the smallest x.
    XMin,
    /// The side at the largest x.
    XMax,
    /// The side at the smallest y.
    YMin,
    /// The side at the largest y.
    YMax,
    /// The side at the smallest z.
    ZMin,
    /// The side at the largest z.
    ZMax,
}

impl Side {
    /// The axis normal to the side (0 = x, 1 = y, 2 = z).
    pub fn axis(self) -> usize {
        match self {
            Side::XMin | Side::XMax => 0,
            Side::YMin | Side::YMax => 1,
            Side::ZMin | Side::ZMax => 2,
        }
    }

    /// Whether the side is at the largest coordinate.
    pub fn is_max(self) -> bool {
        matches!(self, Side::XMax | Side::YMax | Side::ZMax)
    }
}

/// Parameters of [`generate_platen`]. Lengths in metres.
#[derive(Clone, Debug, PartialEq)]
pub struct PlatenSpec {
    /// Side of the specimen's bounding box the platen touches.
    pub side: Side,
    /// Platen thickness along the side's normal.
    pub thickness: f64,
    /// Extent along the two other axes, in axis order (e.g. x then z for a
    /// `±y` platen); `None` takes the specimen's extent on that axis. The
    /// platen is centred on the specimen.
    pub extent: [Option<f64>; 2],
    /// Target element size.
    pub element_size: f64,
    /// Region of the platen's tets.
    pub region: Region,
}

/// Meshes a platen touching `side` of the bounding box `(lo, hi)` of the
/// specimen: its contact face lies in the plane of that side. Boundary
/// groups are those of [`generate_box`]; the face against the specimen is
/// the box side opposite `side` (e.g. `ymin` for a `+y` platen).
///
/// # Errors
/// [`MeshError::InvalidParameter`] for a bad thickness, extent or size.
pub fn generate_platen(spec: &PlatenSpec, lo: [f64; 3], hi: [f64; 3]) -> Result<TetMesh, MeshError> {
    let t = positive("thickness", spec.thickness)?;
    let axis = spec.side.axis();
    let others = [(axis + 1) % 3, (axis + 2) % 3];
    let others = if others[0] < others[1] { others } else { [others[1], others[0]] };
    let mut min = [0.0; 3];
    let mut max = [0.0; 3];
    for (k, &a) in others.iter().enumerate() {
        let mid = 0.5 * (lo[a] + hi[a]);
        let w = match spec.extent[k] {
            Some(w) => positive(["extent[0]", "extent[1]"][k], w)?,
            None => hi[a] - lo[a],
        };
        min[a] = mid - 0.5 * w;
        max[a] = mid + 0.5 * w;
    }
    if spec.side.is_max() {
        min[axis] = hi[axis];
        max[axis] = hi[axis] + t;
    } else {
        min[axis] = lo[axis] - t;
        max[axis] = lo[axis];
    }
    generate_box(&BoxSpec {
        min,
        max,
        element_size: spec.element_size,
        jitter: 0.0,
        seed: 0,
        region: spec.region.clone(),
    })
}
