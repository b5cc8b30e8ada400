//! Geometry of a 4-node (linear) tetrahedron.
//!
//! Node numbering follows the usual positive convention: a tet
//! `[a, b, c, d]` is positive when `d` lies on the side of face `abc`
//! that `(b − a) × (c − a)` points to, i.e. when
//! `V = (b − a) · ((c − a) × (d − a)) / 6 > 0`.

use crate::{Real, Vec3};

/// Local node indices of the four faces of a tet, face `i` being the one
/// opposite node `i`. Each face is ordered counter-clockwise seen from
/// outside the tet, so `(p1 − p0) × (p2 − p0)` is the outward normal of a
/// positive tet.
pub const FACES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];

/// Local node pairs of the six edges of a tet.
pub const EDGES: [[usize; 2]; 6] = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]];

/// Signed volume `V = (b − a) · ((c − a) × (d − a)) / 6`.
#[inline]
pub fn signed_volume(p: &[Vec3; 4]) -> Real {
    (p[1] - p[0]).dot(&(p[2] - p[0]).cross(&(p[3] - p[0]))) / 6.0
}

/// Area of the triangle `p0 p1 p2`.
#[inline]
pub fn triangle_area(p0: &Vec3, p1: &Vec3, p2: &Vec3) -> Real {
    0.5 * (p1 - p0).cross(&(p2 - p0)).norm()
}

/// Sum of the four face areas.
pub fn surface_area(p: &[Vec3; 4]) -> Real {
    FACES.iter().map(|f| triangle_area(&p[f[0]], &p[f[1]], &p[f[2]])).sum()
}

/// Radius of the inscribed sphere, `r = 3|V| / A` with `A` the surface area.
pub fn inradius(p: &[Vec3; 4]) -> Real {
    let a = surface_area(p);
    if a > 0.0 { 3.0 * signed_volume(p).abs() / a } else { 0.0 }
}

/// Lengths of the six edges, in [`EDGES`] order.
pub fn edge_lengths(p: &[Vec3; 4]) -> [Real; 6] {
    EDGES.map(|[i, j]| (p[j] - p[i]).norm())
}

/// Aspect ratio `γ = ℓ_max / (2√6 · r)`, with `ℓ_max` the longest edge and
/// `r` the inradius; the factor makes `γ = 1` for a regular tet, and `γ`
/// grows without bound as the tet degenerates (infinite for zero volume).
pub fn aspect_ratio(p: &[Vec3; 4]) -> Real {
    let lmax = edge_lengths(p).into_iter().fold(0.0, Real::max);
    let r = inradius(p);
    if r > 0.0 { lmax / (2.0 * 6.0_f64.sqrt() * r) } else { Real::INFINITY }
}

/// Centroid of the four points.
#[inline]
pub fn centroid(p: &[Vec3; 4]) -> Vec3 {
    (p[0] + p[1] + p[2] + p[3]) * 0.25
}

#[cfg(test)]
mod tests {
    use super::*;

    fn regular() -> [Vec3; 4] {
        [Vec3::new(1.0, 1.0, 1.0), Vec3::new(1.0, -1.0, -1.0), Vec3::new(-1.0, 1.0, -1.0), Vec3::new(-1.0, -1.0, 1.0)]
    }

    #[test]
    fn unit_corner_tet_has_volume_one_sixth() {
        let p = [Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()];
        assert!((signed_volume(&p) - 1.0 / 6.0).abs() < 1e-15);
    }

    #[test]
    fn regular_tet_has_aspect_ratio_one() {
        let p = regular();
        assert!(signed_volume(&p).abs() > 0.0);
        assert!((aspect_ratio(&p) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn face_normals_point_outward() {
        let p = [Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()];
        let c = centroid(&p);
        for f in FACES {
            let n = (p[f[1]] - p[f[0]]).cross(&(p[f[2]] - p[f[0]]));
            assert!(n.dot(&(p[f[0]] - c)) > 0.0, "face {f:?} points inward");
        }
    }
}
