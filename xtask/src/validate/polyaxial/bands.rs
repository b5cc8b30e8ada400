//! The orientation of shear bands and of shear-failed faces, measured in
//! the plane normal to the intermediate stress σ2 (z), where Mohr–Coulomb
//! puts the two conjugate shear planes at ±(45° + φ/2) from the least
//! compressive axis σ1 (x) (the paper's Eq. 24).
//!
//! Two measures, both area-weighted:
//! - **Bands** (the macroscopic fracture): a Hough transform of the
//!   centroids of the shear-failed faces projected on x–y. For a band
//!   direction `θ` (from +x, in [0°, 180°)), the centroids are projected on
//!   the band's normal and the slab of width `w` holding the most failed
//!   area scores `θ`; the best `θ` is the main band, the best `θ` at least
//!   [`CONJUGATE_GAP`] away from it is the conjugate set. Ties go to the
//!   direction whose slab is thinnest (smallest RMS spread).
//! - **Facets** (the element-scale criterion): the angle between each
//!   shear-failed face's plane and the x axis, `β = 90° − acos|n·x̂|`,
//!   summarised by its area-weighted median.

/// Smallest angle between the main band and a conjugate one, degrees.
pub const CONJUGATE_GAP: f64 = 20.0;

/// A failed face seen in the x–y plane: its centroid `(x, y)` (m), its
/// area (m²) and its unit normal.
#[derive(Debug, Clone, Copy)]
pub struct Facet {
    /// Centroid x and y, m.
    pub at: (f64, f64),
    /// Area, m².
    pub area: f64,
    /// Unit normal.
    pub normal: [f64; 3],
}

/// A band direction and how much of the failed area its best slab holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Band {
    /// Direction from +x, degrees in [0, 180).
    pub theta: f64,
    /// Share of the failed area inside its slab.
    pub share: f64,
}

impl Band {
    /// The acute angle between the band and the x axis, degrees in [0, 90].
    pub fn angle_to_x(&self) -> f64 {
        self.theta.min(180.0 - self.theta)
    }
}

/// The best slab of width `width` (m) along the normal of direction
/// `theta` (degrees): the share of the area of `facets` it holds and the
/// area-weighted RMS distance of its facets from their mean (m), which
/// breaks ties between directions in favour of the thinnest band.
fn slab(facets: &[Facet], theta: f64, width: f64) -> (f64, f64) {
    let (s, c) = theta.to_radians().sin_cos();
    let mut proj: Vec<(f64, f64)> = facets.iter().map(|f| (-s * f.at.0 + c * f.at.1, f.area)).collect();
    proj.sort_by(|a, b| a.0.total_cmp(&b.0));
    let total: f64 = proj.iter().map(|p| p.1).sum();
    let spread = |w: &[(f64, f64)]| {
        let a: f64 = w.iter().map(|p| p.1).sum();
        let mean = w.iter().map(|p| p.0 * p.1).sum::<f64>() / a;
        (w.iter().map(|p| (p.0 - mean).powi(2) * p.1).sum::<f64>() / a).sqrt()
    };
    let (mut best, mut rms, mut inside, mut lo) = (0.0f64, f64::INFINITY, 0.0, 0);
    for hi in 0..proj.len() {
        inside += proj[hi].1;
        while proj[hi].0 - proj[lo].0 > width {
            inside -= proj[lo].1;
            lo += 1;
        }
        if inside >= best {
            let r = spread(&proj[lo..=hi]);
            if inside > best || r < rms {
                (best, rms) = (inside, r);
            }
        }
    }
    if total > 0.0 { (best / total, rms) } else { (0.0, 0.0) }
}

/// The main band and, if any direction at least [`CONJUGATE_GAP`] away
/// scores, the conjugate one: directions every degree, slab width `width`.
pub fn bands(facets: &[Facet], width: f64) -> Option<(Band, Band)> {
    if facets.is_empty() {
        return None;
    }
    let scores: Vec<(Band, f64)> = (0..180)
        .map(f64::from)
        .map(|theta| {
            let (share, rms) = slab(facets, theta, width);
            (Band { theta, share }, rms)
        })
        .collect();
    let best = |ok: &dyn Fn(f64) -> bool| {
        scores
            .iter()
            .filter(|b| ok(b.0.theta))
            .max_by(|a, b| {
                a.0.share.total_cmp(&b.0.share).then(b.1.total_cmp(&a.1)).then(b.0.theta.total_cmp(&a.0.theta))
            })
            .map(|b| b.0)
    };
    let main = best(&|_| true)?;
    let gap = |t: f64| {
        let d = (t - main.theta).abs();
        d.min(180.0 - d)
    };
    let conjugate = best(&|t| gap(t) >= CONJUGATE_GAP)?;
    Some((main, conjugate))
}

/// Area-weighted median of the facets' plane angle to the x axis,
/// `β = 90° − acos|n·x̂|`, degrees; `None` without facets.
pub fn facet_angle(facets: &[Facet]) -> Option<f64> {
    let mut b: Vec<(f64, f64)> =
        facets.iter().map(|f| (90.0 - f.normal[0].abs().min(1.0).acos().to_degrees(), f.area)).collect();
    b.sort_by(|x, y| x.0.total_cmp(&y.0));
    let total: f64 = b.iter().map(|x| x.1).sum();
    let mut acc = 0.0;
    for (angle, area) in b {
        acc += area;
        if acc >= 0.5 * total {
            return Some(angle);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Facets evenly spread along a line through `(x0, y0)` at `theta`.
    fn line(x0: f64, y0: f64, theta: f64, n: usize, area: f64) -> Vec<Facet> {
        let (s, c) = theta.to_radians().sin_cos();
        (0..n)
            .map(|i| {
                let t = -0.3 + 0.6 * i as f64 / (n - 1) as f64;
                Facet { at: (x0 + t * c, y0 + t * s), area, normal: [-s, c, 0.0] }
            })
            .collect()
    }

    #[test]
    fn a_band_and_its_conjugate_are_found_at_their_angles() {
        let mut f = line(0.25, 0.25, 61.7, 60, 1.0);
        f.extend(line(0.3, 0.2, 180.0 - 61.7, 30, 1.0));
        let (main, conj) = bands(&f, 0.02).unwrap();
        assert!((main.theta - 62.0).abs() <= 1.0, "{main:?}");
        assert!((conj.theta - 118.0).abs() <= 1.0, "{conj:?}");
        assert!((main.angle_to_x() - 61.7).abs() <= 1.0 && (conj.angle_to_x() - 61.7).abs() <= 1.0);
        // The main band holds its own 60 facets and about one of the other's.
        assert!(main.share > 60.0 / 90.0 && main.share < 63.0 / 90.0, "{main:?}");
    }

    #[test]
    fn a_compact_cluster_scores_the_same_in_every_direction() {
        let f: Vec<Facet> = (0..50)
            .map(|i| Facet {
                at: (0.01 * f64::from(i % 5), 0.01 * f64::from(i / 5 % 5)),
                area: 1.0,
                normal: [1.0, 0.0, 0.0],
            })
            .collect();
        let (main, conj) = bands(&f, 0.2).unwrap();
        assert_eq!((main.share, conj.share), (1.0, 1.0));
    }

    #[test]
    fn facet_angles_are_measured_from_the_x_axis() {
        let f = line(0.0, 0.0, 61.7, 11, 1.0);
        assert!((facet_angle(&f).unwrap() - 61.7).abs() < 1e-9);
        let vertical = [Facet { at: (0.0, 0.0), area: 1.0, normal: [1.0, 0.0, 0.0] }];
        assert!((facet_angle(&vertical).unwrap() - 90.0).abs() < 1e-12);
        assert_eq!(facet_angle(&[]), None);
    }
}
