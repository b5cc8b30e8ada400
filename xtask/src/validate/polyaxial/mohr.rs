//! Fig. 13 of the paper: the Mohr circles of the polyaxial test and the
//! envelopes of its materials (the prediction itself is
//! `femdem_post::mohr`).

use std::path::Path;

use anyhow::Result;
use femdem_post::mohr::Stresses;

use crate::validate::plot;

/// Fig. 13: the three circles and the envelopes of `materials`
/// (`(label, c, φ)`), in the paper's sign convention (tension positive).
pub fn figure(path: &Path, s: Stresses, materials: &[(String, f64, f64)]) -> Result<()> {
    let circle = |a: f64, b: f64| -> Vec<(f64, f64)> {
        let (m, r) = (0.5 * (a + b), 0.5 * (b - a));
        (0..=180).map(|i| f64::from(i).to_radians()).map(|t| (-1e-6 * (m + r * t.cos()), 1e-6 * r * t.sin())).collect()
    };
    let mut series = vec![
        ("circle (σ1, σ3)".to_owned(), circle(s.least, s.most)),
        ("circle (σ1, σ2)".to_owned(), circle(s.least, s.intermediate)),
        ("circle (σ2, σ3)".to_owned(), circle(s.intermediate, s.most)),
    ];
    let far = 1.1 * s.most;
    for (label, c, phi) in materials {
        let t = phi.to_radians().tan();
        // From σ = 0 (τ = c) to the most compressive stress; the tension
        // side is cut off at σ = c / tan φ (Eq. 5) and not drawn.
        series.push((format!("envelope {label}"), vec![(0.0, 1e-6 * c), (-1e-6 * far, 1e-6 * (c + far * t))]));
    }
    plot::lines(
        path,
        "Polyaxial test: Mohr circles and envelopes (Fig. 13)",
        "normal stress σ (MPa, tension +)",
        "shear stress τ (MPa)",
        &series,
    )
}
