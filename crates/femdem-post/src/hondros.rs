//! The elastic stress in a disc loaded along a diameter, and femdem's
//! stress at the disc's centre compared with it.
//!
//! Closed form (two diametral point loads P on a disc of radius R,
//! diameter D, thickness t; Frocht's superposition of two Flamant fields
//! and a uniform tension; y along the load, compression negative):
//!
//! σx = −(2P / πt) [x² (R − y) / r₁⁴ + x² (R + y) / r₂⁴ − 1/D]
//! σy = −(2P / πt) [(R − y)³ / r₁⁴ + (R + y)³ / r₂⁴ − 1/D]
//!
//! with r₁² = x² + (R − y)², r₂² = x² + (R + y)². At the centre it gives
//! Hondros' σx = 2P/(πDt) and σy = −6P/(πDt). Flat platens spread the load
//! over a narrow strip; at the centre that changes the stresses by well
//! under 1% while the strip is under a tenth of the diameter.

use anyhow::{Result, bail};

use crate::brazilian::Disc;
use crate::frames::Grid;

/// `(σx, σy)` of the point-load solution at `(x, y)` (centre at the
/// origin) for load `p` (N), Pa.
pub fn point_load(disc: Disc, p: f64, x: f64, y: f64) -> (f64, f64) {
    let (r, d, t) = (0.5 * disc.diameter, disc.diameter, disc.thickness);
    let r1 = (x * x + (r - y) * (r - y)).powi(2);
    let r2 = (x * x + (r + y) * (r + y)).powi(2);
    let k = -2.0 * p / (std::f64::consts::PI * t);
    let sx = k * (x * x * (r - y) / r1 + x * x * (r + y) / r2 - 1.0 / d);
    let sy = k * ((r - y).powi(3) / r1 + (r + y).powi(3) / r2 - 1.0 / d);
    (sx, sy)
}

/// The centre zone's mean stresses: femdem's and the closed form's.
#[derive(Debug, Clone, Copy)]
pub struct Centre {
    /// Volume-weighted mean σx of femdem's tets, Pa.
    pub sx: f64,
    /// Volume-weighted mean σy of femdem's tets, Pa.
    pub sy: f64,
    /// The closed form's σx averaged over the same tets, Pa.
    pub sx_exact: f64,
    /// The closed form's σy averaged over the same tets, Pa.
    pub sy_exact: f64,
    /// Tets averaged.
    pub tets: usize,
}

/// Radius of the centre zone as a fraction of the disc's radius.
pub const ZONE: f64 = 0.25;

/// Averages over the disc's tets (region 0) whose centroids lie within
/// [`ZONE`] of the radius from the axis, in frame `grid` under load `p`.
/// The disc's axis is z through the origin, as in the base case.
pub fn centre(grid: &Grid, disc: Disc, p: f64) -> Result<Centre> {
    let (nc, stress) = grid.cell("stress")?;
    let (_, region) = grid.cell("region")?;
    if nc != 9 {
        bail!("stress has {nc} components, not 9");
    }
    let mut acc = [0.0; 5];
    let mut tets = 0;
    for c in 0..grid.cells.len() {
        let [x, y, _] = grid.centroid(c);
        if region[c] != 0.0 || x.hypot(y) > ZONE * 0.5 * disc.diameter {
            continue;
        }
        let v = grid.tet_volume(c);
        let (ex, ey) = point_load(disc, p, x, y);
        for (a, s) in acc.iter_mut().zip([stress[9 * c], stress[9 * c + 4], ex, ey, 1.0]) {
            *a += v * s;
        }
        tets += 1;
    }
    if tets == 0 {
        bail!("no disc tet near the centre");
    }
    let v = acc[4];
    Ok(Centre { sx: acc[0] / v, sy: acc[1] / v, sx_exact: acc[2] / v, sy_exact: acc[3] / v, tets })
}

#[cfg(test)]
mod tests {
    use super::*;

    const DISC: Disc = Disc { diameter: 0.04, thickness: 0.015 };

    #[test]
    fn centre_values_are_hondros() {
        let p = 1000.0;
        let (sx, sy) = point_load(DISC, p, 0.0, 0.0);
        let s0 = 2.0 * p / (std::f64::consts::PI * DISC.diameter * DISC.thickness);
        assert!((sx / s0 - 1.0).abs() < 1e-12);
        assert!((sy / s0 + 3.0).abs() < 1e-12);
    }

    #[test]
    fn tension_is_uniform_along_the_loaded_diameter() {
        // σx = 2P/(πDt) at every point of x = 0 (a textbook property).
        let s0 = 2.0 * 500.0 / (std::f64::consts::PI * DISC.diameter * DISC.thickness);
        for y in [-0.015, -0.005, 0.0, 0.01, 0.019] {
            let (sx, _) = point_load(DISC, 500.0, 0.0, y);
            assert!((sx / s0 - 1.0).abs() < 1e-12, "y = {y}: {sx}");
        }
    }

    #[test]
    fn the_rim_is_free_of_normal_stress_on_the_unloaded_diameter() {
        // At (R, 0) the rim's normal is x and τxy = 0 by symmetry: σx = 0.
        let (sx, _) = point_load(DISC, 800.0, 0.5 * DISC.diameter, 0.0);
        let s0 = 2.0 * 800.0 / (std::f64::consts::PI * DISC.diameter * DISC.thickness);
        assert!(sx.abs() < 1e-12 * s0, "σx at the rim: {sx}");
    }
}
