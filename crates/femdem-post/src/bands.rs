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
//!   direction whose slab is thinnest (smallest RMS spread). Since the
//!   conjugate set is scored on all the faces, a slab through the dense
//!   cluster where failure started can win it; [`mirrored`] scores the
//!   mirrored family alone, with the main band's faces set aside.
//! - **Facets** (the element-scale criterion): the angle to x of each
//!   shear-failed face's trace on the x–y plane, `β = 90° − atan(|n_y| /
//!   |n_x|)` from its unit normal `n` (61.7° for a face on the Test 1 plane),
//!   summarised by the median weighted by area × `(n_x² + n_y²)`, so that a
//!   face counts by how nearly it contains z as the Mohr–Coulomb planes do.

use anyhow::Result;
use femdem_fracture::FailureMode;

use crate::frames::Grid;

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
    let (share, rms, _) = slab_at(facets, theta, width);
    (share, rms)
}

/// [`slab`], with the best slab's bounds along the normal `(lo, hi)`, m.
fn slab_at(facets: &[Facet], theta: f64, width: f64) -> (f64, f64, (f64, f64)) {
    let (s, c) = theta.to_radians().sin_cos();
    let mut proj: Vec<(f64, f64)> = facets.iter().map(|f| (-s * f.at.0 + c * f.at.1, f.area)).collect();
    proj.sort_by(|a, b| a.0.total_cmp(&b.0));
    let total: f64 = proj.iter().map(|p| p.1).sum();
    let spread = |w: &[(f64, f64)]| {
        let a: f64 = w.iter().map(|p| p.1).sum();
        let mean = w.iter().map(|p| p.0 * p.1).sum::<f64>() / a;
        (w.iter().map(|p| (p.0 - mean).powi(2) * p.1).sum::<f64>() / a).sqrt()
    };
    let (mut best, mut rms, mut inside, mut lo, mut bounds) = (0.0f64, f64::INFINITY, 0.0, 0, (0.0, 0.0));
    for hi in 0..proj.len() {
        inside += proj[hi].1;
        while proj[hi].0 - proj[lo].0 > width {
            inside -= proj[lo].1;
            lo += 1;
        }
        if inside >= best {
            let r = spread(&proj[lo..=hi]);
            if inside > best || r < rms {
                (best, rms, bounds) = (inside, r, (proj[lo].0, proj[hi].0));
            }
        }
    }
    if total > 0.0 { (best / total, rms, bounds) } else { (0.0, 0.0, bounds) }
}

/// Half-width of the window of directions around the mirror of the main
/// band, 180° − θ, that [`mirrored`] searches, degrees.
pub const MIRROR_WINDOW: f64 = 15.0;

/// The mirrored family beside the main band `main` (found by [`bands`] on
/// `facets` with slab width `width`): the facets inside the main band's
/// best slab are set aside, and the direction within [`MIRROR_WINDOW`] of
/// 180° − θ whose best slab holds the most of the rest scores, by its share
/// of the area of all `facets`. `None` when nothing is left.
pub fn mirrored(facets: &[Facet], main: Band, width: f64) -> Option<Band> {
    let total: f64 = facets.iter().map(|f| f.area).sum();
    let (_, _, (lo, hi)) = slab_at(facets, main.theta, width);
    let (s, c) = main.theta.to_radians().sin_cos();
    let rest: Vec<Facet> = facets
        .iter()
        .filter(|f| {
            let d = -s * f.at.0 + c * f.at.1;
            d < lo || d > hi
        })
        .copied()
        .collect();
    let rest_area: f64 = rest.iter().map(|f| f.area).sum();
    if rest.is_empty() || total <= 0.0 {
        return None;
    }
    let centre = 180.0 - main.theta;
    let window = MIRROR_WINDOW as i32;
    (-window..=window)
        .map(|k| (centre + f64::from(k)).rem_euclid(180.0))
        .map(|theta| {
            let (share, rms) = slab(&rest, theta, width);
            (Band { theta, share: share * rest_area / total }, rms)
        })
        .max_by(ranked)
        .map(|b| b.0)
}

/// The order of scored directions `(band, rms)`: the larger share, then the
/// thinner slab, then the smaller angle wins.
fn ranked(a: &(Band, f64), b: &(Band, f64)) -> std::cmp::Ordering {
    a.0.share.total_cmp(&b.0.share).then(b.1.total_cmp(&a.1)).then(b.0.theta.total_cmp(&a.0.theta))
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
    let best =
        |ok: &dyn Fn(f64) -> bool| scores.iter().filter(|b| ok(b.0.theta)).max_by(|a, b| ranked(a, b)).map(|b| b.0);
    let main = best(&|_| true)?;
    let gap = |t: f64| {
        let d = (t - main.theta).abs();
        d.min(180.0 - d)
    };
    let conjugate = best(&|t| gap(t) >= CONJUGATE_GAP)?;
    Some((main, conjugate))
}

/// The weighted median of the facets' trace angle to the x axis,
/// `β = 90° − atan(|n_y| / |n_x|)`, degrees (see the module
/// documentation); `None` without facets or weight.
pub fn facet_angle(facets: &[Facet]) -> Option<f64> {
    let mut b: Vec<(f64, f64)> = facets
        .iter()
        .map(|f| {
            let (nx, ny) = (f.normal[0].abs(), f.normal[1].abs());
            (90.0 - ny.atan2(nx).to_degrees(), f.area * (nx * nx + ny * ny))
        })
        .filter(|x| x.1 > 0.0)
        .collect();
    b.sort_by(|x, y| x.0.total_cmp(&y.0));
    let total: f64 = b.iter().map(|x| x.1).sum();
    let mut acc = 0.0;
    for (angle, weight) in b {
        acc += weight;
        if acc >= 0.5 * total {
            return Some(angle);
        }
    }
    None
}

/// The faces of a fracture frame (`<case>_fractures.pvd`: triangles with
/// cell data `mode`) that failed in `mode`, as [`Facet`]s: centroid, area
/// and unit normal; degenerate (zero-area) triangles are left out.
///
/// # Errors
/// When the frame has no `mode` cell data.
pub fn failed_facets(grid: &Grid, mode: FailureMode) -> Result<Vec<Facet>> {
    let (_, modes) = grid.cell("mode")?;
    let code = f64::from(mode.code());
    let mut out = Vec::new();
    for (c, cell) in grid.cells.iter().enumerate().filter(|(c, _)| modes[*c] == code) {
        let p = [0, 1, 2].map(|k| grid.points[cell[k]]);
        let (u, v) = ([0, 1, 2].map(|k| p[1][k] - p[0][k]), [0, 1, 2].map(|k| p[2][k] - p[0][k]));
        let n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        if len > 0.0 {
            let at = grid.centroid(c);
            out.push(Facet { at: (at[0], at[1]), area: 0.5 * len, normal: n.map(|x| x / len) });
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failed_facets_are_the_faces_of_one_mode_of_a_fracture_frame_series() {
        let dir = std::env::temp_dir().join(format!("femdem-post-facets-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // Two shear triangles (one in the plane x = 1, one degenerate) and
        // a tensile one, written as `femdem run` writes its fracture frames.
        let points =
            [[1.0, 0.0, 0.0], [1.0, 2.0, 0.0], [1.0, 0.0, 3.0], [0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0]];
        let triangles = [[0, 1, 2], [3, 4, 5], [3, 0, 1]];
        let mode = [2.0, 2.0, 1.0];
        let fields = [femdem_vtk::Field::scalar("mode", &mode)];
        let frame = femdem_vtk::Frame::new(&points, &[]).with_triangles(&triangles).with_cell_fields(&fields);
        let mut series = femdem_vtk::SeriesWriter::new(&dir, "case_fractures").unwrap();
        series.write(1e-3, &frame).unwrap();
        let frames = crate::frames::series(&series.pvd_path()).unwrap();
        assert_eq!(frames.len(), 1);
        let grid = Grid::read(&frames[0].1).unwrap();
        let shear = failed_facets(&grid, FailureMode::Shear).unwrap();
        assert_eq!(shear.len(), 1, "the degenerate triangle is left out");
        let f = shear[0];
        assert!((f.area - 3.0).abs() < 1e-12 && (f.at.0 - 1.0).abs() < 1e-12 && (f.at.1 - 2.0 / 3.0).abs() < 1e-12);
        assert!((f.normal[0].abs() - 1.0).abs() < 1e-12, "{:?}", f.normal);
        assert_eq!(failed_facets(&grid, FailureMode::Tensile).unwrap().len(), 1);
        assert!(failed_facets(&grid, FailureMode::Mixed).unwrap().is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
    }

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
    fn the_mirrored_family_is_scored_without_the_main_band_or_a_corner_cluster() {
        // A main band at 61.7°, a shorter mirrored one crossing it, and a
        // dense cluster at a corner on the main band's line, which the
        // conjugate measure of `bands` takes for the second set.
        let mut f = line(0.25, 0.25, 61.7, 60, 1.0);
        f.extend(line(0.3, 0.2, 180.0 - 61.7, 20, 1.0));
        let (s, c) = 61.7f64.to_radians().sin_cos();
        f.extend((0..25).map(|i| Facet {
            at: (0.25 + 0.3 * c + 0.004 * f64::from(i % 5), 0.25 + 0.3 * s + 0.004 * f64::from(i / 5)),
            area: 1.0,
            normal: [1.0, 0.0, 0.0],
        }));
        let total = f.len() as f64;
        let (main, conj) = bands(&f, 0.02).unwrap();
        assert!((main.theta - 62.0).abs() <= 1.0, "{main:?}");
        // `bands` scores its second set on all the faces: the slab through
        // the cluster and part of the main band outscores the mirrored line.
        assert!((conj.theta - 118.0).abs() > 8.0, "{conj:?}");
        let m = mirrored(&f, main, 0.02).unwrap();
        assert!((m.theta - 118.0).abs() <= 1.0, "{m:?}");
        // The mirrored line's 20 facets, less the one or two inside the
        // main band's slab.
        assert!(m.share > 17.0 / total && m.share <= 20.0 / total, "{m:?}");
        // One band alone leaves nothing in the mirrored family.
        let one = line(0.25, 0.25, 61.7, 60, 1.0);
        let (main, _) = bands(&one, 0.02).unwrap();
        assert_eq!(mirrored(&one, main, 0.02), None);
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
        // A face normal to z has no trace direction and no weight.
        let flat = Facet { at: (0.0, 0.0), area: 1.0, normal: [0.0, 0.0, 1.0] };
        assert_eq!(facet_angle(&[flat]), None);
        // Tilting a face about its trace leaves the trace angle alone.
        let (s, c) = 61.7f64.to_radians().sin_cos();
        let tilted = Facet { at: (0.0, 0.0), area: 1.0, normal: [-s * 0.6, c * 0.6, 0.8] };
        assert!((facet_angle(&[tilted, flat]).unwrap() - 61.7).abs() < 1e-9);
        assert_eq!(facet_angle(&[]), None);
    }
}
