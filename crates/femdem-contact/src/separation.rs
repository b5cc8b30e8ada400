//! A narrow-phase filter for detection: whether a face plane of one tet
//! keeps the other more than a gap away.
//!
//! Bounding spheres are loose around tets: in a mesh of pre-existing
//! fractures most sphere pairs that NBS keeps are tets a layer or two apart
//! that cannot touch before the next detection. A separating face plane
//! proves it. If a face plane `H` of tet A (outward unit normal `n`) has
//! every node of tet B more than `g` beyond it, `n·(x_B − x_H) > g`, and A
//! lies behind it, `n·(x_A − x_H) ≤ 0`, then after every node has moved by at
//! most `g/2` the nodes of A are still at most `g/2` beyond `H` and those of
//! B more than `g/2`: `H` shifted by `g/2` separates the two convex hulls,
//! they do not overlap, and their Eq. 17 force is zero. With `g` the
//! detection buffer `b` and re-detection once a node has moved more than
//! `b/2`, dropping such pairs changes no force, bit for bit.
//!
//! Only the eight face planes are tried (not the 36 edge–edge directions of
//! the full separating-axis test): the filter may keep a pair that is
//! separated, never drop one that may touch.

use femdem_core::tet::FACES;
use femdem_core::{Real, Vec3};

/// Whether a face plane of `a` has every node of `b` more than `gap` (m)
/// beyond it, or a face plane of `b` every node of `a`. Faces of zero area
/// prove nothing and are skipped; the orientation of the tets does not
/// matter (each face's outward side is the one away from its opposite
/// node).
pub fn separated_by_face_plane(a: &[Vec3; 4], b: &[Vec3; 4], gap: Real) -> bool {
    one_way(a, b, gap) || one_way(b, a, gap)
}

/// Whether a face plane of `a` has all of `b` more than `gap` beyond it.
fn one_way(a: &[Vec3; 4], b: &[Vec3; 4], gap: Real) -> bool {
    FACES.iter().enumerate().any(|(opposite, face)| {
        let [p0, p1, p2] = face.map(|k| a[k]);
        let cross = (p1 - p0).cross(&(p2 - p0));
        let norm = cross.norm();
        if norm <= 0.0 {
            return false;
        }
        let mut n = cross / norm;
        if n.dot(&(a[opposite] - p0)) > 0.0 {
            n = -n;
        }
        b.iter().all(|q| n.dot(&(q - p0)) > gap)
    })
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;
    use proptest::strategy::ValueTree;

    use super::*;
    use crate::tet_tet_contact;

    fn unit() -> [Vec3; 4] {
        [Vec3::zeros(), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 0.0, 1.0)]
    }

    /// The unit tet mirrored below `z = 0` and moved down by `d`: its face
    /// `z = −d` faces the unit tet's face `z = 0` across a gap `d`.
    fn below(d: Real) -> [Vec3; 4] {
        let t = unit();
        [t[0], t[2], t[1], -t[3]].map(|p| p - Vec3::new(0.0, 0.0, d))
    }

    #[test]
    fn a_gap_across_facing_faces_separates_only_beyond_it() {
        let a = unit();
        let b = below(0.1);
        assert!(separated_by_face_plane(&a, &b, 0.09));
        assert!(separated_by_face_plane(&b, &a, 0.09), "symmetric");
        assert!(!separated_by_face_plane(&a, &b, 0.1), "the gap must be exceeded");
        // Touching faces (the two sides of a fracture) are never separated.
        assert!(!separated_by_face_plane(&a, &below(0.0), 0.0));
        // Overlapping tets are not.
        assert!(!separated_by_face_plane(&a, &below(-0.2), 0.0));
    }

    #[test]
    fn the_orientation_of_the_tets_does_not_matter() {
        let a = unit();
        let flipped = [a[0], a[2], a[1], a[3]];
        let b = below(0.1);
        assert_eq!(separated_by_face_plane(&flipped, &b, 0.05), separated_by_face_plane(&a, &b, 0.05));
        assert!(separated_by_face_plane(&flipped, &[b[0], b[2], b[1], b[3]], 0.05));
    }

    #[test]
    fn a_flat_tet_proves_nothing_by_its_zero_area_faces() {
        let flat = [Vec3::zeros(), Vec3::new(1.0, 0.0, 0.0), Vec3::new(2.0, 0.0, 0.0), Vec3::new(3.0, 0.0, 0.0)];
        let far = unit().map(|p| p + Vec3::new(0.0, 0.0, 5.0));
        // Every face of `flat` has zero area; `far`'s face z = 5 still
        // separates them.
        assert!(separated_by_face_plane(&flat, &far, 1.0));
        assert!(!separated_by_face_plane(&flat, &flat, 0.0));
    }

    fn point(spread: f64) -> impl Strategy<Value = Vec3> {
        (-spread..spread, -spread..spread, -spread..spread).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    /// A random tet, positively oriented as the contact force expects.
    fn tet(at: f64) -> impl Strategy<Value = [Vec3; 4]> {
        (point(1.0), point(1.0), point(1.0), point(1.0), point(at)).prop_map(|(a, b, c, d, shift)| {
            let t = [a, b, c, d].map(|p| p + shift);
            if femdem_core::tet::signed_volume(&t) < 0.0 { [t[0], t[2], t[1], t[3]] } else { t }
        })
    }

    proptest! {
        /// The soundness the detection relies on: pairs separated with gap
        /// `g` have no contact force after every node moved by up to `g/2`.
        #[test]
        fn separated_pairs_have_no_force_after_moves_of_half_the_gap(
            a in tet(1.5),
            b in tet(1.5),
            gap in 0.0..0.5f64,
            moves in proptest::collection::vec(point(1.0), 8),
        ) {
            prop_assume!(separated_by_face_plane(&a, &b, gap));
            let shift = |p: &Vec3, m: &Vec3| p + m * (0.5 * gap / m.norm().max(1.0));
            let a2 = [0, 1, 2, 3].map(|k| shift(&a[k], &moves[k]));
            let b2 = [0, 1, 2, 3].map(|k| shift(&b[k], &moves[4 + k]));
            let c = tet_tet_contact(&a2, &b2, 1e10);
            prop_assert!(c.centre.is_none());
            prop_assert!(c.on_a.iter().chain(&c.on_b).all(|f| *f == Vec3::zeros()));
        }
    }

    /// The proptest above compares many separated pairs, not a vacuous few.
    #[test]
    fn the_random_pairs_are_often_separated() {
        let mut runner = proptest::test_runner::TestRunner::deterministic();
        let strategy = (tet(1.5), tet(1.5));
        let n = 1000;
        let separated = (0..n)
            .filter(|_| {
                let (a, b) = strategy.new_tree(&mut runner).unwrap().current();
                separated_by_face_plane(&a, &b, 0.1)
            })
            .count();
        assert!(separated > n / 10, "{separated} of {n}");
    }
}
