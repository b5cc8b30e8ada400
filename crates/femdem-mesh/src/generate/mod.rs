//! Mesh generators that need no external tool. Each is reproducible: the
//! same parameters (and seed, where there is one) give the same mesh, bit
//! for bit, and every tet it makes has positive volume.

mod block;
mod clearance;
mod extrude;
mod platen;
mod prism;
mod traces;

pub use block::{BoxSpec, generate_box};
pub use clearance::{Feature, NearMiss, closest_approach};
pub use extrude::{
    AREA_FACTOR, ExtrusionSpec, MIN_CLEARANCE, Outline, circle_segments, estimated_tets, generate_extrusion,
    polygon_area,
};
pub use platen::{PlatenSpec, Side, generate_platen};
pub use traces::{TRACE_TOLERANCE, TraceNetwork, trace_network};

use crate::MeshError;

/// Rejects a non-finite or non-positive length.
pub(crate) fn positive(name: &'static str, v: f64) -> Result<f64, MeshError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(MeshError::InvalidParameter { name, reason: format!("must be a finite length > 0 m, got {v}") })
    }
}

/// Guards against a parameter set that would make an absurd number of
/// elements (a typo such as `element_size = 1e-6` on a 1 m domain).
pub(crate) const MAX_CELLS: f64 = 2.0e8;
