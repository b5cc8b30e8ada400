//! A box meshed by a randomly perturbed Freudenthal (Kuhn) lattice.
//!
//! The box is cut into `nx × ny × nz` cells of size close to the target;
//! each cell is split into the six tets of the Freudenthal triangulation
//! (the paths from corner `(0,0,0)` to `(1,1,1)` along the three axes in the
//! six possible orders), which is conforming across cells. Vertices are then
//! moved by a seeded uniform random offset of up to `jitter · h` per
//! component so that a regular lattice does not bias crack paths; a vertex
//! on a face of the box keeps that face's coordinate, so the box stays a box.
//! The smallest altitude of a Kuhn tet is `h/√2`, and `jitter ≤ 0.15` keeps
//! every tet positive (checked by property tests).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::{MAX_CELLS, positive, prism::orient};
use crate::{BoundaryGroup, FaceRef, MeshError, Region, TetMesh};

/// Parameters of [`generate_box`]. Lengths in metres.
#[derive(Clone, Debug, PartialEq)]
pub struct BoxSpec {
    /// Lower corner.
    pub min: [f64; 3],
    /// Upper corner.
    pub max: [f64; 3],
    /// Target edge length of the lattice cells.
    pub element_size: f64,
    /// Random vertex offset as a fraction of the cell size, in `[0, 0.15]`.
    pub jitter: f64,
    /// Seed of the random offsets.
    pub seed: u64,
    /// Region given to every tet.
    pub region: Region,
}

/// The largest allowed [`BoxSpec::jitter`].
pub const MAX_JITTER: f64 = 0.15;

/// Meshes a box. Boundary groups `xmin`, `xmax`, `ymin`, `ymax`, `zmin`,
/// `zmax` hold its six sides.
///
/// # Errors
/// [`MeshError::InvalidParameter`] for an empty box, a bad size or jitter.
pub fn generate_box(spec: &BoxSpec) -> Result<TetMesh, MeshError> {
    let h = positive("element_size", spec.element_size)?;
    if !(0.0..=MAX_JITTER).contains(&spec.jitter) {
        return Err(MeshError::InvalidParameter {
            name: "jitter",
            reason: format!("must lie in [0, {MAX_JITTER}] (fraction of the element size), got {}", spec.jitter),
        });
    }
    let mut n = [0usize; 3];
    let mut step = [0.0; 3];
    for k in 0..3 {
        for (name, v) in [("min", spec.min[k]), ("max", spec.max[k])] {
            if !v.is_finite() {
                return Err(MeshError::InvalidParameter {
                    name,
                    reason: format!("must be finite on every axis, got {v} on axis {k}"),
                });
            }
        }
        let len = spec.max[k] - spec.min[k];
        positive(["size x", "size y", "size z"][k], len).map_err(|_| MeshError::InvalidParameter {
            name: "max",
            reason: format!("max must exceed min on every axis (axis {k}: {} ≤ {})", spec.max[k], spec.min[k]),
        })?;
        n[k] = ((len / h).round() as usize).max(1);
        step[k] = len / n[k] as f64;
    }
    // In floating point: the cell counts saturate at usize::MAX for a huge
    // box, and their integer product would wrap to a small number (it did:
    // max = [1e300, 1e300, 1] made 1 × 6 tets pass, then pushed vertices until memory ran out).
    if n.iter().map(|&c| c as f64).product::<f64>() * 6.0 > MAX_CELLS {
        // The counts from the lengths, unsaturated; their product by its
        // logarithm, which cannot overflow.
        let c = |k: usize| ((spec.max[k] - spec.min[k]) / h).round().max(1.0);
        let shown = |x: f64| if x < 1e15 { format!("{x:.0}") } else { format!("{x:.3e}") };
        let log = (0..3).map(|k| c(k).log10()).sum::<f64>() + 6f64.log10();
        let total = if log < 300.0 { shown(10f64.powf(log)) } else { format!("about 1e{log:.0}") };
        return Err(MeshError::InvalidParameter {
            name: "element_size",
            reason: format!(
                "{h:e} m would make {total} tets ({}×{}×{} cells of 6); refuse above {MAX_CELLS:e}",
                shown(c(0)),
                shown(c(1)),
                shown(c(2))
            ),
        });
    }
    let [nx, ny, nz] = n;
    let vid = |i: usize, j: usize, k: usize| (i + (nx + 1) * (j + (ny + 1) * k)) as u32;

    let mut rng = ChaCha8Rng::seed_from_u64(spec.seed);
    let mut coords = Vec::with_capacity((nx + 1) * (ny + 1) * (nz + 1));
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                let idx = [i, j, k];
                let mut c = [0.0; 3];
                for a in 0..3 {
                    c[a] = spec.min[a] + idx[a] as f64 * step[a];
                    let interior = idx[a] > 0 && idx[a] < n[a];
                    if spec.jitter > 0.0 {
                        // Draw even on the boundary so the stream does not depend on position.
                        let r: f64 = rng.random_range(-1.0..=1.0);
                        if interior {
                            c[a] += r * spec.jitter * step[a];
                        }
                    }
                }
                coords.push(c);
            }
        }
    }

    // The six Freudenthal paths: axis orders.
    const PATHS: [[usize; 3]; 6] = [[0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]];
    let mut tets = Vec::with_capacity(nx * ny * nz * 6);
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                for path in PATHS {
                    let mut at = [i, j, k];
                    let mut t = [vid(i, j, k); 4];
                    for (s, &axis) in path.iter().enumerate() {
                        at[axis] += 1;
                        t[s + 1] = vid(at[0], at[1], at[2]);
                    }
                    tets.push(orient(t, &coords));
                }
            }
        }
    }

    let mut mesh = TetMesh {
        tet_region: vec![0; tets.len()],
        coords,
        tets,
        regions: vec![spec.region.clone()],
        ..Default::default()
    };
    mesh.boundary = box_sides(&mesh, spec.min, spec.max, step);
    Ok(mesh)
}

/// Boundary faces grouped by the box side they lie on.
fn box_sides(mesh: &TetMesh, min: [f64; 3], max: [f64; 3], step: [f64; 3]) -> Vec<BoundaryGroup> {
    const NAMES: [[&str; 2]; 3] = [["xmin", "xmax"], ["ymin", "ymax"], ["zmin", "zmax"]];
    let mut groups: Vec<BoundaryGroup> =
        NAMES.iter().flatten().map(|n| BoundaryGroup { name: (*n).to_string(), faces: Vec::new() }).collect();
    for t in 0..mesh.tets.len() {
        for local in 0..4u8 {
            let f = FaceRef { tet: t as u32, local };
            let nodes = f.nodes(&mesh.tets).map(|v| mesh.coords[v as usize]);
            for axis in 0..3 {
                let tol = 1e-9 * step[axis];
                for (side, plane) in [min[axis], max[axis]].into_iter().enumerate() {
                    if nodes.iter().all(|c| (c[axis] - plane).abs() <= tol) {
                        groups[2 * axis + side].faces.push(f);
                    }
                }
            }
        }
    }
    groups
}
