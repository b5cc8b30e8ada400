//! An extruded circle is meshed as the polygon inscribed in it, with sides
//! of at most `element_size` (`femdem_mesh::generate::circle_segments`):
//! `n` sides hold `n sin(2π/n) / 2π` of the circle's area, so a coarse
//! size makes a smaller, faceted body (8 sides: 10% less area, a diameter
//! across the flats 7.6% short). Worth a warning that says by how much.

use femdem_mesh::generate::circle_segments;

/// Area shortfall of the inscribed polygon above which the circle is
/// called out (1%: 24 sides or fewer, as the count is a multiple of 4, so
/// an `element_size` at or above `2πr/24` ≈ 0.262 r). The bundled discs
/// have 32 sides and more (0.6%).
pub const AREA_SHORTFALL: f64 = 0.01;

/// The fraction of a circle's area that its inscribed polygon of `n`
/// sides lacks: `1 − n sin(2π/n) / 2π`.
pub fn area_shortfall(n: usize) -> f64 {
    let a = std::f64::consts::TAU / n as f64;
    1.0 - n as f64 * a.sin() / std::f64::consts::TAU
}

/// The warning for extrusion part `key`, a circle of `radius` meshed at
/// element size `h`, when its polygon lacks more than [`AREA_SHORTFALL`]
/// of the circle's area; `None` otherwise.
pub fn circle_warning(key: &str, radius: f64, h: f64) -> Option<String> {
    if !(radius > 0.0 && h > 0.0 && radius.is_finite() && h.is_finite()) {
        return None;
    }
    let n = circle_segments(radius, h);
    let short = area_shortfall(n);
    let flats = 1.0 - (std::f64::consts::PI / n as f64).cos();
    (short > AREA_SHORTFALL).then(|| {
        format!(
            "{key}: the circle of radius {radius} m is meshed as a polygon of {n} sides at element_size = {h} m: \
             {:.1}% less area than the circle, and a diameter across the flats {:.1}% short; an element_size \
             below {:.3e} m (28 sides or more) keeps the area within {}%",
            100.0 * short,
            100.0 * flats,
            std::f64::consts::TAU * radius / 24.0,
            100.0 * AREA_SHORTFALL
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shortfall_is_the_inscribed_polygons() {
        // An inscribed square holds 2/π of the circle, a hexagon 3√3/2π.
        assert!((area_shortfall(4) - (1.0 - 2.0 / std::f64::consts::PI)).abs() < 1e-15);
        let hexagon = 3.0 * 3f64.sqrt() / (2.0 * std::f64::consts::PI);
        assert!((area_shortfall(6) - (1.0 - hexagon)).abs() < 1e-15);
        assert!(area_shortfall(24) > AREA_SHORTFALL && area_shortfall(28) < AREA_SHORTFALL);
    }

    #[test]
    fn a_coarse_circle_is_called_out_and_a_fine_one_is_not() {
        // h = r: 8 sides.
        let w = circle_warning("mesh.parts[0]", 0.025, 0.025).unwrap();
        assert!(w.contains("polygon of 8 sides") && w.contains("10.0% less area"), "{w}");
        assert!(w.contains("7.6% short"), "{w}");
        // The README disc (r = 20 mm, h = 4 mm): 32 sides, 0.6%.
        assert!(circle_warning("mesh.parts[0]", 0.020, 0.004).is_none());
        // The size the warning suggests is within the bound.
        let suggested = std::f64::consts::TAU * 0.025 / 24.0;
        assert!(circle_warning("k", 0.025, suggested * 0.999).is_none());
        assert!(circle_warning("k", 0.025, suggested * 1.2).is_some());
    }
}
