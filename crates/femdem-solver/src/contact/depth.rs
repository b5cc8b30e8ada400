//! How deep the tets in contact have gone into each other, for the
//! history's `contact_depth_max` and the warning about parts that overlap
//! at the start.

use femdem_core::tet::{FACES, triangle_area};
use femdem_core::{Real, Vec3};

use super::Contact;
use crate::model::Model;

/// The overlap depth of two tets, m: over the eight face normals of the
/// two, the least overlap of their projections, `min_n (min(max_A n·x,
/// max_B n·x) − max(min_A n·x, min_B n·x))`, clamped at 0 — the
/// separating-axis estimate of the distance that parts them, exact for
/// two faces pressed flat (and for a vertex or an edge pushed through a
/// face), an upper bound where edges cross; 0 for tets that only touch.
pub(crate) fn overlap_depth(a: &[Vec3; 4], b: &[Vec3; 4]) -> Real {
    let mut depth = Real::INFINITY;
    for p in [a, b] {
        for [i, j, k] in FACES {
            let n = (p[j] - p[i]).cross(&(p[k] - p[i]));
            let norm = n.norm();
            if norm == 0.0 {
                continue;
            }
            let n = n / norm;
            let span = |q: &[Vec3; 4]| {
                q.iter().map(|x| n.dot(x)).fold((Real::INFINITY, Real::NEG_INFINITY), |(l, h), d| (l.min(d), h.max(d)))
            };
            let ((la, ha), (lb, hb)) = (span(a), span(b));
            depth = depth.min(ha.min(hb) - la.max(lb));
        }
    }
    if depth.is_finite() { depth.max(0.0) } else { 0.0 }
}

/// The shortest altitude `3V/A_max` of tet `t` in the reference
/// configuration, m.
fn altitude(model: &Model, t: u32) -> Real {
    let p = model.tets[t as usize].map(|n| model.x0[n as usize]);
    let largest = FACES.iter().map(|f| triangle_area(&p[f[0]], &p[f[1]], &p[f[2]])).fold(0.0, Real::max);
    3.0 * model.tet_ref[t as usize].volume / largest
}

/// The overlap depth of pair `(a, b)` at positions `x(node)` over the
/// smaller of the two tets' shortest reference altitudes.
fn depth_share(model: &Model, x: &impl Fn(u32) -> Vec3, a: u32, b: u32) -> Real {
    let depth = overlap_depth(&model.tets[a as usize].map(x), &model.tets[b as usize].map(x));
    if depth > 0.0 { depth / altitude(model, a).min(altitude(model, b)) } else { 0.0 }
}

impl Contact {
    /// The largest overlap of the pairs in contact at the last pass, as a
    /// share of the element: over those pairs, [`overlap_depth`] at the
    /// positions `x(node)` over the smaller of the two tets' shortest
    /// reference altitudes `3V/A_max` (at 1 a face has gone through a
    /// whole tet). 0 with no pair in contact. A measure of whether the
    /// penalty is stiff enough for the mesh: Eq. 17 assumes small overlaps.
    pub fn deepest_overlap(&self, model: &Model, x: impl Fn(u32) -> Vec3) -> Real {
        self.in_contact.iter().map(|&(a, b)| depth_share(model, &x, a, b)).fold(0.0, Real::max)
    }

    /// The pairs that started overlapped and are in contact now whose
    /// depth share at `x(node)` exceeds `least`, and the largest share:
    /// tets that really overlap, not faces that only touch (as across a
    /// pre-existing fracture at the start, where Eq. 17 may still see a
    /// contact of zero depth).
    pub fn started_overlaps(&self, model: &Model, x: impl Fn(u32) -> Vec3, least: Real) -> (usize, Real) {
        // A count and a maximum: the map's order does not matter.
        self.started
            .keys()
            .map(|&(a, b)| depth_share(model, &x, a, b))
            .filter(|&d| d > least)
            .fold((0, 0.0), |(n, m), d| (n + 1, m.max(d)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> [Vec3; 4] {
        [Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()]
    }

    #[test]
    fn a_face_pushed_in_is_as_deep_as_it_went_and_touching_is_zero() {
        // B below A's face z = 0, its top face 0.01 above it.
        let b = [
            Vec3::new(0.0, 0.0, 0.01),
            Vec3::new(1.0, 0.0, 0.01),
            Vec3::new(0.0, 1.0, 0.01),
            Vec3::new(0.2, 0.2, -1.0),
        ];
        assert!((overlap_depth(&unit(), &b) - 0.01).abs() < 1e-15);
        assert_eq!(overlap_depth(&b, &unit()), overlap_depth(&unit(), &b));
        let touching = b.map(|p| p - Vec3::new(0.0, 0.0, 0.01));
        assert_eq!(overlap_depth(&unit(), &touching), 0.0);
        let apart = unit().map(|p| p + Vec3::new(3.0, 0.0, 0.0));
        assert_eq!(overlap_depth(&unit(), &apart), 0.0);
    }

    #[test]
    fn a_vertex_pushed_through_a_face_is_as_deep_as_it_went() {
        // B's apex 0.02 above A's face z = 0, inside A.
        let b = [
            Vec3::new(0.2, 0.2, 0.02),
            Vec3::new(-1.0, -1.0, -1.0),
            Vec3::new(2.0, -1.0, -1.0),
            Vec3::new(-1.0, 2.0, -1.0),
        ];
        assert!((overlap_depth(&unit(), &b) - 0.02).abs() < 1e-15, "{}", overlap_depth(&unit(), &b));
    }
}
