//! One candidate pair of the contact pass: the normal potential force
//! (Eq. 17), the Eq. 18 ramp, and Coulomb friction.

use femdem_contact::tet_tet_forces;
use femdem_core::{Real, Vec3};

/// What one pair in contact contributes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PairForce {
    /// The two tets.
    pub tets: [u32; 2],
    /// Normal (potential) force on the nodes of each tet, N.
    pub normal: [[Vec3; 4]; 2],
    /// Friction force on the second tet's centroid (its opposite on the
    /// first's), N.
    pub friction: Vec3,
    /// The friction spring after this step, oriented as second tet relative
    /// to the first with the tets in index order (see [`spring_key`]).
    pub spring: Vec3,
    /// Elastic energy of the friction spring, `½ k_t |s|²`, J.
    pub spring_energy: Real,
}

/// The key of a pair, smaller tet first.
pub(crate) fn spring_key(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

/// Whether the axis-aligned boxes of two node sets overlap.
pub(crate) fn boxes_overlap(pa: &[Vec3; 4], pb: &[Vec3; 4]) -> bool {
    (0..3).all(|k| {
        let (lo_a, hi_a) = pa.iter().fold((Real::INFINITY, Real::NEG_INFINITY), |(l, h), p| (l.min(p[k]), h.max(p[k])));
        let (lo_b, hi_b) = pb.iter().fold((Real::INFINITY, Real::NEG_INFINITY), |(l, h), p| (l.min(p[k]), h.max(p[k])));
        lo_a <= hi_b && lo_b <= hi_a
    })
}

/// The inputs of one pair.
pub(crate) struct PairInput<'a> {
    pub tets: [u32; 2],
    pub x: [[Vec3; 4]; 2],
    pub v: [[Vec3; 4]; 2],
    /// `V^{1/3}` of the smaller tet, m (the friction spring's length scale).
    pub size: Real,
    pub penalty: Real,
    pub mu: Real,
    /// Eq. 18's `n_c / n_total` while the ramp lasts, else 1.
    pub ramp: Real,
    /// The pair's friction spring from the last step, if it was in contact.
    pub spring: Option<&'a Vec3>,
    pub dt: Real,
}

/// Evaluates one pair; `None` when the two tets do not overlap.
///
/// Normal force: Eq. 17 (`femdem_contact::tet_tet_forces`), times the
/// Eq. 18 ramp factor `n_c / n_total` for a joint that failed in
/// compression.
///
/// Friction: the pair carries a tangential spring `s`, stretched by the
/// tangential relative velocity of the two centroids, `s += v_t Δt`, and kept
/// in the current tangent plane (normal `n̂` along the pair's normal force
/// `N`); the friction force is `−k_t s` with `k_t = p ℓ` (`ℓ` the smaller
/// tet's `V^{1/3}`, so the tangential stiffness is of the order of the
/// normal one), capped at the Coulomb limit `μ |N|`, where the spring slips
/// (is shortened to the limit). It acts on the centroids (a quarter on each
/// node).
pub(crate) fn evaluate(input: PairInput<'_>) -> Option<PairForce> {
    let [a, b] = input.tets;
    let [pa, pb] = &input.x;
    if !boxes_overlap(pa, pb) {
        return None;
    }
    let (mut fa, mut fb) = tet_tet_forces(pa, pb, input.penalty);
    if input.ramp != 1.0 {
        for f in fa.iter_mut().chain(fb.iter_mut()) {
            *f *= input.ramp;
        }
    }
    let normal: Vec3 = fb.iter().sum();
    let n_mag = normal.norm();
    if n_mag == 0.0 && fa.iter().all(|f| f.norm() == 0.0) {
        return None;
    }
    let mut out = PairForce {
        tets: input.tets,
        normal: [fa, fb],
        friction: Vec3::zeros(),
        spring: Vec3::zeros(),
        spring_energy: 0.0,
    };
    if input.mu > 0.0 && n_mag > 0.0 {
        let n = normal / n_mag;
        let va: Vec3 = input.v[0].iter().sum::<Vec3>() / 4.0;
        let vb: Vec3 = input.v[1].iter().sum::<Vec3>() / 4.0;
        let rel = vb - va;
        let vt = rel - n * rel.dot(&n);
        // Springs are stored as (larger index) relative to (smaller index).
        let sign = if a < b { 1.0 } else { -1.0 };
        let mut spring = input.spring.copied().unwrap_or_else(Vec3::zeros) * sign;
        spring -= n * spring.dot(&n);
        spring += vt * input.dt;
        let kt = input.penalty * input.size;
        let limit = input.mu * n_mag;
        let mut ft = -spring * kt;
        if ft.norm() > limit {
            ft *= limit / ft.norm();
            spring = -ft / kt;
        }
        out.friction = ft;
        out.spring = spring * sign;
        out.spring_energy = 0.5 * kt * spring.norm_squared();
    }
    Some(out)
}
