//! The tet–tet penalty potential contact force (Eq. 17; Munjiza & Andrews
//! 2000):
//!
//! * no overlap, no force;
//! * tets overlapping face to face repel along the faces' normal, more
//!   the deeper they overlap;
//! * the forces on the eight nodes sum to zero and have no net torque about
//!   any point (each piece's force and its reaction act at the same point:
//!   exact up to round-off, checked to 1e-12 of the force scale);
//! * the force does not depend on which tet is called the contactor (both
//!   one-way passes are summed), to round-off;
//! * the contact centre (where friction is to act) lies in both tets (its
//!   barycentric coordinates in each are ≥ 0, to round-off) and is the same
//!   whichever tet is the contactor; apart, there is none;

use femdem_contact::{tet_tet_contact, tet_tet_forces};
use femdem_core::Vec3;
use proptest::prelude::*;

/// A regular tet (positively oriented: nodes 2 and 3 of the usual corner
/// list swapped), node 0 at `center + size (1, 1, 1) / 2`.
fn regular(center: Vec3, size: f64) -> [Vec3; 4] {
    [Vec3::new(1.0, 1.0, 1.0), Vec3::new(1.0, -1.0, -1.0), Vec3::new(-1.0, -1.0, 1.0), Vec3::new(-1.0, 1.0, -1.0)]
        .map(|v| center + v * (0.5 * size))
}

fn oriented(mut t: [Vec3; 4]) -> [Vec3; 4] {
    if femdem_core::tet::signed_volume(&t) < 0.0 {
        t.swap(2, 3);
    }
    t
}

fn sum(f: &[Vec3; 4]) -> Vec3 {
    f.iter().sum()
}

#[test]
fn apart_there_is_no_force() {
    let a = regular(Vec3::zeros(), 1.0);
    let b = regular(Vec3::new(3.0, 0.0, 0.0), 1.0);
    let (fa, fb) = tet_tet_forces(&a, &b, 1e9);
    assert!(fa.iter().chain(&fb).all(|f| f.norm() == 0.0));
    assert_eq!(tet_tet_contact(&a, &b, 1e9).centre, None);
}

/// Barycentric coordinates of `q` in tet `t`.
fn barycentric(t: &[Vec3; 4], q: &Vec3) -> [f64; 4] {
    let m = femdem_core::Mat3::from_columns(&[t[1] - t[0], t[2] - t[0], t[3] - t[0]]).try_inverse().unwrap();
    let l = m * (q - t[0]);
    [1.0 - l.x - l.y - l.z, l.x, l.y, l.z]
}

/// Two regular tets face to face: `b` is `a` reflected through its centre
/// and moved along the normal of `a`'s face 0 so that the two faces overlap
/// by `δ`. The push on `b` along that normal is positive and grows with `δ`
/// (for oblique contacts the force follows the faces, not the line of
/// centres, so only this arrangement has a sign known in advance).
#[test]
fn face_to_face_overlap_repels_more_the_deeper_it_is() {
    let a = regular(Vec3::zeros(), 1.0);
    // Face 0 of `a` (opposite node 0 at +(1,1,1)/2) faces −(1,1,1).
    let d = -Vec3::new(1.0, 1.0, 1.0).normalize();
    let r_in = 2f64.sqrt() / (2.0 * 6f64.sqrt());
    let mut last = 0.0;
    for delta in [0.0, 0.01, 0.03, 0.06, 0.1] {
        let k = 2.0 * r_in - delta;
        let b = oriented(a.map(|v| -v + d * k));
        let (fa, fb) = tet_tet_forces(&a, &b, 1e9);
        let push = sum(&fb).dot(&d);
        assert!(push >= last, "δ = {delta}: push {push} after {last}");
        assert!((sum(&fa) + sum(&fb)).norm() <= 1e-12 * sum(&fb).norm().max(1.0));
        last = push;
    }
    assert!(last > 0.0, "overlapping faces must repel");
}

fn tet() -> impl Strategy<Value = [Vec3; 4]> {
    prop::array::uniform4(prop::array::uniform3(-1.0f64..1.0)).prop_map(|p| oriented(p.map(Vec3::from))).prop_filter(
        "well-shaped",
        |t| {
            let v = femdem_core::tet::signed_volume(t);
            v > 0.02
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn momentum_is_conserved_and_roles_do_not_matter(a in tet(), b in tet(), shift in prop::array::uniform3(-0.5f64..0.5)) {
        let b = b.map(|p| p + Vec3::from(shift));
        let (fa, fb) = tet_tet_forces(&a, &b, 1e9);
        let scale = fa.iter().chain(&fb).map(|f| f.norm()).fold(0.0, f64::max);
        prop_assume!(scale > 0.0);
        prop_assert!((sum(&fa) + sum(&fb)).norm() <= 1e-12 * scale);
        let origin = Vec3::new(0.3, -2.0, 1.0);
        let torque: Vec3 = a.iter().zip(&fa).chain(b.iter().zip(&fb)).map(|(x, f)| (x - origin).cross(f)).sum();
        prop_assert!(torque.norm() <= 1e-11 * scale * 4.0, "torque {}", torque.norm());
        let (gb, ga) = tet_tet_forces(&b, &a, 1e9);
        for k in 0..4 {
            prop_assert!((ga[k] - fa[k]).norm() <= 1e-12 * scale);
            prop_assert!((gb[k] - fb[k]).norm() <= 1e-12 * scale);
        }
        let centre = tet_tet_contact(&a, &b, 1e9).centre.unwrap();
        for t in [&a, &b] {
            let l = barycentric(t, &centre);
            prop_assert!(l.iter().all(|&x| x >= -1e-12), "centre outside a tet: {l:?}");
        }
        let swapped = tet_tet_contact(&b, &a, 1e9).centre.unwrap();
        prop_assert!((swapped - centre).norm() <= 1e-12, "centre {centre} vs {swapped}");
    }
}

/// Shallow face-to-face overlap has a closed form: each face sinks `δ` into
/// the other tet, where `φ = 4 δ / H` (`H` the altitude on that face, `4 r`
/// for a regular tet of inradius `r`), over the overlap of the two faces — a
/// regular tet's face and its point reflection overlap in a hexagon of 2/3
/// of the face — so the two one-way passes give `F = 2 p A_ov 4 δ / H`.
/// Near the edge of the hexagon, within `O(δ)`, the other sub-tets take
/// over: at `δ = H / 100` the estimate holds to a few percent.
#[test]
fn shallow_face_overlap_matches_the_closed_form() {
    let a = regular(Vec3::zeros(), 1.0);
    let d = -Vec3::new(1.0, 1.0, 1.0).normalize();
    let r_in = 2f64.sqrt() / (2.0 * 6f64.sqrt());
    let h = 4.0 * r_in;
    let face_area = 3f64.sqrt() / 4.0 * 2.0; // edge √2
    let delta = h / 100.0;
    let b = oriented(a.map(|v| -v + d * (2.0 * r_in - delta)));
    let p = 1e9;
    let (_, fb) = tet_tet_forces(&a, &b, p);
    let expected = 2.0 * p * (2.0 / 3.0 * face_area) * 4.0 * delta / h;
    let push = sum(&fb).dot(&d);
    assert!((push / expected - 1.0).abs() < 0.05, "push {push} vs {expected}");
}
