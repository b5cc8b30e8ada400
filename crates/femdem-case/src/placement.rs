//! A mesh far from the origin. A position `x` carries a round-off of
//! about `ε |x|` (`ε` = 2.2·10⁻¹⁶), and every step adds to it an increment
//! `v Δt` that is some 10⁻⁶ of an edge under quasi-static loading, while a
//! joint opens by about 10⁻⁵ of an edge before its peak (Eq. 5–9 with the
//! default penalty): a mesh lying `10⁵` of its shortest edges or more
//! from the origin (an MSH file in site coordinates, a UTM easting of
//! 5·10⁵ m under millimetre elements) loses those increments and openings
//! to round-off, and its runs change with where it sits. femdem does not
//! translate the mesh by itself (its inputs — boxes, probes, outputs — are
//! all in the case's coordinates); it says so, and proposes a round shift
//! for an MSH part's `translate` key, which moves the file's coordinates
//! into the case's as they are read (`mesh.rs`, `place`).

use femdem_mesh::TetMesh;

/// The ratio of the mesh's largest coordinate to its shortest edge above
/// which [`warning`] speaks: `ε` times it is 2.2·10⁻¹¹ of an edge, which
/// the per-step increments (about 10⁻⁶ of an edge) feel at 10⁻⁵ each. The
/// bundled cases lie within 60 of their shortest edges from the origin.
pub const RATIO: f64 = 1e5;

/// The warning for a mesh whose largest coordinate is more than
/// [`RATIO`] times its shortest edge *because it sits away from the
/// origin* (its bounding box's centre farther from the origin than the
/// box is wide; a centred mesh with a wide range of sizes is not helped
/// by a translation), with the figures; `None` otherwise.
pub fn warning(mesh: &TetMesh) -> Option<String> {
    let (lo, hi) = mesh.bounding_box()?;
    let centre = [0, 1, 2].map(|k| 0.5 * (lo[k] + hi[k]));
    let offset = centre.iter().map(|c| c * c).sum::<f64>().sqrt();
    let extent = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
    let far = (0..3).map(|k| lo[k].abs().max(hi[k].abs())).fold(0.0f64, f64::max);
    if !(far.is_finite() && extent > 0.0 && offset > extent) {
        return None;
    }
    let (shortest, _) = crate::refinement::shortest_edge(mesh, |_, _| true)?;
    if !(shortest > 0.0 && far > RATIO * shortest) {
        return None;
    }
    let roundoff = f64::EPSILON * far;
    // A round shift that brings the centre within the size: rounded to a
    // multiple of p = 10^k ≤ extent, each coordinate of the centre ends
    // within p/2, the centre within √3 p/2 < extent (so this warning is not
    // given again). Rounded by an integer power of ten (exact) so that it
    // prints as a round number.
    let k = extent.log10().floor();
    let shift = if k < 0.0 {
        let q = 10f64.powf(-k);
        centre.map(|c| -(c * q).round() / q)
    } else {
        let p = 10f64.powf(k);
        centre.map(|c| -(c / p).round() * p)
    };
    Some(format!(
        "mesh: the mesh's centre lies {offset:.4e} m from the origin, {:.1e} times its size ({extent:.3e} m) and \
         {:.1e} times its shortest edge ({shortest:.3e} m): a coordinate there carries a round-off of about \
         {roundoff:.1e} m, {:.1e} of that edge, which a step's position increments (some 10⁻⁶ of an edge) and the \
         joints' openings before their peak (some 10⁻⁵) feel, so results change with where the mesh sits; \
         move the mesh near the origin, e.g. by [{}, {}, {}] m: for an MSH part, add that to its `translate` \
         (and give the case's boxes and points in the shifted coordinates), or change the coordinates in the \
         file or the case",
        offset / extent,
        far / shortest,
        roundoff / shortest,
        shift[0] + 0.0,
        shift[1] + 0.0,
        shift[2] + 0.0
    ))
}

#[cfg(test)]
mod tests {
    use femdem_mesh::Region;
    use femdem_mesh::generate::{BoxSpec, generate_box};

    /// A 10 mm cube of 5 mm cells at the origin, at 1 m, and at a UTM-like
    /// (5·10⁵, 5·10⁶) m: only the last is 10⁵ of its shortest edge (some
    /// 4 mm with the jitter) away, and its warning gives the distance of
    /// its centre, √(5² + 50²)·10⁵ m, and the round-off, ε × 5·10⁶ m ≈
    /// 1.1·10⁻⁹ m. A mesh centred on the origin with a huge range of sizes
    /// is not warned: translating it would not help.
    #[test]
    fn a_mesh_far_from_the_origin_is_a_warning() {
        let at = |o: [f64; 3]| {
            let spec = BoxSpec {
                min: o,
                max: [o[0] + 0.01, o[1] + 0.01, o[2] + 0.01],
                element_size: 0.005,
                jitter: 0.1,
                seed: 1,
                region: Region { name: "rock".into(), breakable: true },
            };
            super::warning(&generate_box(&spec).unwrap())
        };
        assert_eq!(at([0.0; 3]), None);
        assert_eq!(at([1.0, 1.0, 0.0]), None);
        let w = at([5e5, 5e6, 0.0]).expect("a warning");
        assert!(w.contains("the mesh's centre lies 5.0249e6 m from the origin"), "{w}");
        assert!(w.contains("a round-off of about 1.1e-9 m"), "{w}");
        // The cube is 17 mm across its diagonal: a shift in multiples of
        // 10 mm, which brings its centre (5e5 + 0.005, 5e6 + 0.005, 0.005)
        // within 10 mm of the origin.
        let by = &w[w.find("by [").expect("a shift") + 4..];
        let shift: Vec<f64> = by[..by.find(']').unwrap()].split(", ").map(|c| c.parse().unwrap()).collect();
        let centre = [5e5 + 0.005, 5e6 + 0.005, 0.005];
        for k in 0..3 {
            assert!((centre[k] + shift[k]).abs() <= 0.005 + 1e-9, "{w}");
            assert!(((shift[k] * 100.0).round() - shift[k] * 100.0).abs() < 1e-6, "{w}");
        }
        let mut centred = generate_box(&BoxSpec {
            min: [-0.005; 3],
            max: [0.005; 3],
            element_size: 0.005,
            jitter: 0.0,
            seed: 1,
            region: Region { name: "rock".into(), breakable: true },
        })
        .unwrap();
        centred.coords.push([1e3, 0.0, 0.0]);
        centred.coords.push([-1e3, 0.0, 0.0]);
        assert_eq!(super::warning(&centred), None);
    }
}
