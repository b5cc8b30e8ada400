//! The static Mohr–Coulomb prediction of the polyaxial test (the paper's
//! Fig. 13): the applied principal stresses as three Mohr circles and each
//! material's envelope `τ = c + σc tan φ` (`σc` the compressive normal
//! stress). The largest circle (σ1, σ3) reaches an envelope when its radius
//! `R = (σ3c − σ1c)/2` equals the envelope's distance from the circle's
//! centre `σm = (σ1c + σ3c)/2`:
//!
//! ```text
//! R_fail = c cos φ + σm sin φ
//! ```
//!
//! so `R / R_fail ≥ 1` means the applied stresses fail the material on
//! planes at `45° + φ/2` from the σ1 axis.

/// The applied principal stresses as compressive magnitudes, Pa:
/// least (σ1, along x), intermediate (σ2, z), most (σ3, y) compressive.
#[derive(Debug, Clone, Copy)]
pub struct Stresses {
    /// |σ1|, Pa.
    pub least: f64,
    /// |σ2|, Pa.
    pub intermediate: f64,
    /// |σ3|, Pa.
    pub most: f64,
}

/// How far the largest Mohr circle reaches towards the envelope of
/// cohesion `c` (Pa) and friction angle `phi` (degrees): `R / R_fail`.
pub fn reach(s: Stresses, c: f64, phi: f64) -> f64 {
    let (r, centre) = (0.5 * (s.most - s.least), 0.5 * (s.most + s.least));
    let phi = phi.to_radians();
    r / (c * phi.cos() + centre * phi.sin())
}

/// The Mohr–Coulomb band angle from the σ1 axis, `45° + φ/2` (Eq. 24).
pub fn band_angle(phi: f64) -> f64 {
    45.0 + 0.5 * phi
}

#[cfg(test)]
mod tests {
    use super::*;

    const PAPER: Stresses = Stresses { least: 3.75e6, intermediate: 9.375e6, most: 15.0e6 };

    #[test]
    fn the_paper_stresses_reach_the_first_two_envelopes_and_not_the_third() {
        // The paper's Fig. 13 says the circle "just touches" all three; the
        // numbers give 1.008, 1.002 and 0.983.
        assert!((reach(PAPER, 0.5e6, 33.4) - 1.0084).abs() < 1e-3);
        assert!((reach(PAPER, 2.0e6, 23.8) - 1.0021).abs() < 1e-3);
        assert!((reach(PAPER, 3.8e6, 12.4) - 0.9827).abs() < 1e-3);
    }

    #[test]
    fn band_angles_follow_eq_24() {
        assert!((band_angle(33.4) - 61.7).abs() < 1e-12);
        assert!((band_angle(23.8) - 56.9).abs() < 1e-12);
        assert!((band_angle(12.4) - 51.2).abs() < 1e-12);
    }
}
