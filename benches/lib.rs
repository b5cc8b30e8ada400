//! Inputs shared by the femdem benchmarks. See `benches/README.md` for what
//! each bench measures; run them with `cargo xtask bench`.

use femdem_mesh::Region;
use femdem_mesh::generate::{BoxSpec, ExtrusionSpec, Outline};

/// A unit box whose Freudenthal lattice has about `tets` tets (6 per cell),
/// jittered by 0.1 of the cell size, breakable.
pub fn box_with_tets(tets: usize) -> BoxSpec {
    let cells_per_axis = ((tets as f64 / 6.0).cbrt()).round().max(1.0);
    BoxSpec {
        min: [0.0; 3],
        max: [1.0; 3],
        element_size: 1.0 / cells_per_axis,
        jitter: 0.1,
        seed: 1,
        region: Region {
            name: "rock".into(),
            breakable: true,
        },
    }
}

/// The Brazilian disc of the reference paper (40 mm × 15 mm, 10 layers).
pub fn disc_extrusion(element_size: f64) -> ExtrusionSpec {
    ExtrusionSpec {
        outline: Outline::Circle {
            center: [0.0, 0.0],
            radius: 0.02,
        },
        traces: vec![],
        z0: 0.0,
        thickness: 0.015,
        element_size,
        layers: Some(10),
        region: Region {
            name: "disc".into(),
            breakable: true,
        },
    }
}
