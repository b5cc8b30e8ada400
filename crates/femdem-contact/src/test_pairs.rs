//! Pairs of tets for the property tests of the contact kernel and its
//! bound: random, face-to-face (the shallow contact of a broken mesh) and
//! sharing a vertex or an edge, at sizes 10⁻³ to 10² and up to 10⁵ sizes
//! from the origin.

use femdem_core::Vec3;
use femdem_core::tet::FACES;
use proptest::prelude::*;

pub(crate) fn point() -> impl Strategy<Value = Vec3> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

pub(crate) fn tet(spread: f64) -> impl Strategy<Value = [Vec3; 4]> {
    (point(), point(), point(), point()).prop_map(move |(a, b, c, d)| {
        let mut t = [a, b, c, d].map(|p| p * spread);
        if femdem_core::tet::signed_volume(&t) < 0.0 {
            t.swap(2, 3);
        }
        t
    })
}

/// `10^e` for `e` in `[lo, hi)`, or exactly zero one time in eight.
pub(crate) fn small(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo..hi, 0..8u8).prop_map(|(e, z)| if z == 0 { 0.0 } else { 10f64.powf(e) })
}

pub(crate) fn positive(mut t: [Vec3; 4]) -> [Vec3; 4] {
    if femdem_core::tet::signed_volume(&t) < 0.0 {
        t.swap(1, 2);
    }
    t
}

/// Both tets scaled by 10⁻³, 1 or 10² and moved by up to 0, 1 or 100
/// (up to 10⁵ times their size), where the margin's `X` counts.
pub(crate) fn placed() -> impl Strategy<Value = (f64, Vec3)> {
    (prop_oneof![Just(1e-3), Just(1.0), Just(1e2)], point(), prop_oneof![Just(0.0), Just(1.0), Just(100.0)])
        .prop_map(|(size, p, s)| (size, p * s))
}

pub(crate) fn place((size, offset): (f64, Vec3), t: [Vec3; 4]) -> [Vec3; 4] {
    t.map(|p| p * size + offset)
}

prop_compose! {
    /// Face-to-face contact, the shallow contact of a broken mesh: `b`
    /// is built on face `f` of `a` (its three nodes, and a fourth beyond
    /// the face), then each of `b`'s nodes is moved by up to `jitter`
    /// (the nodes shared exactly one time in eight), and `b` is slid
    /// along the face and pushed into `a` by `depth` or pulled away.
    pub(crate) fn face_pair()(
        a in tet(1.0),
        f in 0..4usize,
        apex in point(),
        moves in (point(), point(), point(), point()),
        jitter in small(-17.0, -3.0),
        slide in point(),
        slide_size in prop_oneof![Just(0.0), 0.0..0.5f64],
        depth in small(-16.0, -0.5),
        apart in any::<bool>(),
        placing in placed(),
    ) -> ([Vec3; 4], [Vec3; 4]) {
        let [p0, p1, p2] = FACES[f].map(|k| a[k]);
        let n = (p1 - p0).cross(&(p2 - p0)).try_normalize(0.0).unwrap_or(Vec3::x());
        let top = (p0 + p1 + p2) / 3.0 + n * (0.2 + apex.x.abs()) + (apex - n * apex.dot(&n)) * 0.5;
        let shift = (slide - n * slide.dot(&n)) * slide_size + n * if apart { depth } else { -depth };
        let mut b = positive([p0, p2, p1, top]);
        for (p, m) in b.iter_mut().zip([moves.0, moves.1, moves.2, moves.3]) {
            *p += m * jitter + shift;
        }
        (place(placing, a), place(placing, positive(b)))
    }
}

prop_compose! {
    /// Tets sharing one or two nodes (a vertex or an edge of a mesh),
    /// each shared node moved by up to `jitter`.
    pub(crate) fn shared_pair()(
        a in tet(1.0),
        b in tet(1.0),
        shared in 1..3usize,
        first in 0..4usize,
        moves in (point(), point()),
        jitter in small(-17.0, -3.0),
        placing in placed(),
    ) -> ([Vec3; 4], [Vec3; 4]) {
        let mut b = b;
        for (k, m) in [moves.0, moves.1].into_iter().enumerate().take(shared) {
            b[k] = a[(first + k) % 4] + m * jitter;
        }
        (place(placing, a), place(placing, positive(b)))
    }
}
