//! One candidate pair of the contact pass: the normal potential force
//! (Eq. 17), the Eq. 18 ramp, and Coulomb friction at the contact centre.

use femdem_contact::{Bounded, Frame, tet_tet_contact, tet_tet_contact_within_in, tet_tet_gradient};
use femdem_core::{Mat3, Real, Vec3};

use super::settings::{Activation, ContactModel, FrictionTable};

/// What one pair in contact contributes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PairForce {
    /// The two tets.
    pub tets: [u32; 2],
    /// Normal (potential) force on the nodes of each tet, N.
    pub normal: [[Vec3; 4]; 2],
    /// Friction force on the second tet at the contact centre (its opposite
    /// on the first), N.
    pub friction: Vec3,
    /// The barycentric coordinates of the contact centre in each tet: the
    /// shares of the friction force on their nodes.
    pub weights: [[Real; 4]; 2],
    /// The friction spring after this step, oriented as second tet relative
    /// to the first with the tets in index order (see [`spring_key`]).
    pub spring: Vec3,
    /// Elastic energy of the friction spring, `½ k_t |s|²`, J.
    pub spring_energy: Real,
    /// The energy of the normal force, `W = p ∫_{A∩B} (φ_A + φ_B) dV`
    /// times the force's ramp or offset factor, J, with
    /// [`ContactModel::Gradient`] (exact where the factor is 1); 0 with
    /// [`ContactModel::Potential`], whose force has no energy.
    pub energy: Real,
    /// For a pair that started overlapped (it overlapped when newly
    /// allowed to touch and has not separated since): its offset `N_off`
    /// after this step (0 where no offset applies).
    pub started: Option<Real>,
    /// Whether the pair is newly allowed to touch and overlaps: it starts
    /// overlapped now.
    pub fresh: bool,
    /// With [`ContactModel::Gradient`]: whether `normal` is `−∂W/∂x` of
    /// `energy` (no Eq. 18 ramp, no offset, not started overlapped).
    pub exact: bool,
    /// The energy-consistent correction of the normal force's kick
    /// (`onset.rs`), N, on each tet's nodes (zero but with
    /// [`ContactModel::Gradient`]): added to `normal` in the nodal sums.
    pub kick: [[Vec3; 4]; 2],
    /// Whether the pair is in contact; `false` for a pair that has
    /// separated and carries only its `kick`.
    pub touching: bool,
    /// What the correction leaves for the next pass (`onset.rs`).
    pub onset: Option<super::onset::Held>,
}

impl PairForce {
    /// A pair that has separated: no force but the correction `kick`.
    pub(crate) fn kick_only(tets: [u32; 2], kick: [[Vec3; 4]; 2]) -> PairForce {
        PairForce {
            tets,
            normal: [[Vec3::zeros(); 4]; 2],
            friction: Vec3::zeros(),
            weights: [[0.25; 4]; 2],
            spring: Vec3::zeros(),
            spring_energy: 0.0,
            energy: 0.0,
            started: None,
            fresh: false,
            exact: false,
            kick,
            touching: false,
            onset: None,
        }
    }
}

/// A set of tet pairs keyed by [`spring_key`] (see [`PairHasher`]).
pub(crate) type PairSet = std::collections::HashSet<(u32, u32), std::hash::BuildHasherDefault<PairHasher>>;

/// A map from tet pairs keyed by [`spring_key`] (see [`PairHasher`]).
pub(crate) type PairMap<V> = std::collections::HashMap<(u32, u32), V, std::hash::BuildHasherDefault<PairHasher>>;

/// The hasher of the pair state (bonded pairs, friction springs, Eq. 18
/// ramps): FxHash's step `h ← (rotl(h, 5) ⊕ w) · 0x517c_c1b7_2722_0a95` per
/// word, as in rustc, instead of std's SipHash-1-3, whose keyed,
/// DoS-resistant rounds cost some 60 instructions per lookup of two `u32`s
/// (8% of a fragmented step went to the bonded-pair lookups of detection).
/// The keys are tet indices of the model, not input an adversary chooses.
/// Nothing depends on the maps' iteration order: snapshots write them
/// sorted, and the pass only looks keys up, retains by value, or sorts the
/// keys it collects.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct PairHasher(u64);

impl PairHasher {
    #[inline]
    fn add(&mut self, word: u64) {
        self.0 = (self.0.rotate_left(5) ^ word).wrapping_mul(0x517c_c1b7_2722_0a95);
    }
}

impl std::hash::Hasher for PairHasher {
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.add(u64::from(b));
        }
    }

    #[inline]
    fn write_u32(&mut self, n: u32) {
        self.add(u64::from(n));
    }

    #[inline]
    fn finish(&self) -> u64 {
        self.0
    }
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
    /// The two tets' nodes and the velocities of all nodes: read only for
    /// a pair in contact with friction (most candidates are not).
    pub nodes: [[u32; 4]; 2],
    pub v: &'a [Vec3],
    /// `ℓ = V^{1/3}` of the smaller tet, m: the friction spring's length
    /// scale and the negligible forces' (kept per tet by the contact pass:
    /// a cube root per candidate was 5% of a fragmented step).
    pub size: Real,
    pub penalty: Real,
    /// [`super::ContactSettings::model`].
    pub model: ContactModel,
    /// [`super::ContactSettings::negligible`].
    pub negligible: Real,
    /// Whether the pair was in contact at the last pass: clipped before it
    /// is bounded (the order of work only; the result is the same).
    pub clip_first: bool,
    /// What is read only for a pair in contact (most candidates are not):
    /// μ per pair of regions and the tets' regions, the Eq. 18 ramps
    /// (`n_c` per pair, out of `n_total`) and this pair's friction spring
    /// from the last step (zero where it has none).
    pub friction: &'a FrictionTable,
    pub regions: &'a [u16],
    pub ramps: &'a PairMap<u32>,
    pub n_total: Real,
    pub spring: Vec3,
    pub dt: Real,
    /// Whether the pair is newly allowed to touch at this pass (`start.rs`),
    /// how such a pair starts if it overlaps
    /// ([`super::ContactSettings::activation`]), and the pairs that started
    /// overlapped with their offsets (read only for a pair in contact).
    pub fresh: bool,
    /// Whether the pair is the couple of a joint that failed in
    /// compression since the last pass (it starts as with
    /// `Activation::Paper` under `Activation::Couple`).
    pub couple: bool,
    pub activation: Activation,
    pub started: &'a PairMap<Real>,
    /// The pair's Eq. 17 contact (with [`ContactModel::Potential`]: what
    /// `tet_tet_contact_within` or, without a `negligible` threshold,
    /// `tet_tet_contact` gives) computed elsewhere — on a device
    /// (`Contact::pass_with`) — or `None` to compute it here.
    pub geometry: Option<Bounded>,
}

/// The barycentric coordinates of `q` in the tet `p` (`None` if flat).
#[inline(always)]
fn barycentric(p: &[Vec3; 4], q: &Vec3) -> Option<[Real; 4]> {
    let m = Mat3::from_columns(&[p[1] - p[0], p[2] - p[0], p[3] - p[0]]).try_inverse()?;
    let l = m * (q - p[0]);
    Some([1.0 - l.x - l.y - l.z, l.x, l.y, l.z])
}

/// Evaluates one pair; `None` when the two tets do not overlap, when
/// their forces are provably below `negligible · p · ℓ²`
/// ([`super::ContactSettings::negligible`]; then `*negligible_bound` is
/// the bound that showed it), or when every face that overlaps is left out
/// as negligible (`femdem_contact::tet_tet_contact_within`): then the pair
/// is not in contact, and a friction spring or the offset of a pair that
/// started overlapped is dropped with it (the forces dropped are within the
/// same `negligible · p · ℓ²`).
///
/// Normal force: Eq. 17 (`femdem_contact::tet_tet_contact`), times the
/// Eq. 18 ramp factor `n_c / n_total` for a joint that failed in
/// compression (or, with [`Activation::Ramp`], any pair that overlaps
/// when newly allowed to touch), and with [`Activation::Offset`] times
/// `max(0, 1 − N_off / N₁₇)` for a pair that started overlapped; `N` its
/// resultant on the second tet, `n̂ = N / |N|`. A pair that started
/// overlapped is returned while it overlaps with a piece above the
/// negligible, even with no force after its offset (the offset must be
/// kept).
///
/// Friction acts at the contact centre `c` (the force-weighted centre of
/// the clipped overlap pieces, a point of both tets), where the slip is
/// measured and the force applied. With `λ^A`, `λ^B` the barycentric
/// coordinates of `c` in the two tets,
///
/// ```text
/// v_A(c) = Σ_k λ^A_k v_{A,k},   v_B(c) = Σ_k λ^B_k v_{B,k},
/// v_t    = (v_B(c) − v_A(c)) − n̂ (n̂ · (v_B(c) − v_A(c))),
/// s     ← (s − n̂ (n̂ · s)) + v_t Δt,
/// F_t    = −k_t s,  shortened to |F_t| = μ |N| (and s = −F_t / k_t) if longer,
/// f_{B,k} += λ^B_k F_t,   f_{A,k} −= λ^A_k F_t,
/// ```
///
/// `s` the pair's tangential spring (its friction history), `k_t = p ℓ` (`ℓ`
/// the smaller tet's `V^{1/3}`, so the tangential stiffness is of the order
/// of the normal one), capped at the Coulomb limit `μ |N|`, where the
/// spring slips. The nodal forces sum to `±F_t` on each tet and have the
/// moment `c × F_t` (the weights reproduce `c`), so linear and angular
/// momentum are conserved, and their power `Σ f · v = F_t · v_t` is the
/// work of friction on the slip at `c` (what `Contact::book_work` books).
/// A spinning body then feels the friction torque of its contact area, and
/// a rotating fragment slips with the velocity of its contact, not of its
/// centroid.
///
/// Runs in `frame`'s work, the clipping and the bound through it
/// (`femdem_contact::Frame`).
#[inline(always)]
pub(crate) fn evaluate<F: Frame>(
    frame: F,
    input: PairInput<'_>,
    negligible_bound: &mut Option<Real>,
) -> Option<PairForce> {
    let [a, b] = input.tets;
    let [pa, pb] = &input.x;
    if !boxes_overlap(pa, pb) {
        return None;
    }
    let mut energy = 0.0;
    let contact = if input.model == ContactModel::Gradient {
        // No bound: every pair whose boxes overlap is evaluated.
        let g = tet_tet_gradient(pa, pb, input.penalty);
        energy = g.energy;
        g.contact
    } else if let Some(geometry) = input.geometry {
        match geometry {
            Bounded::Negligible(bound) => {
                *negligible_bound = Some(bound);
                return None;
            }
            Bounded::Contact(c) => c,
        }
    } else if input.negligible > 0.0 {
        // Forces up to negligible · p · ℓ², ℓ³ = V the smaller tet's volume,
        // are left out: the whole pair when its bound shows them all below
        // that (the bound is infinite, and the pair evaluated, where it
        // cannot bound), or the faces that carry less.
        let omit = input.negligible * input.size.powi(2);
        match tet_tet_contact_within_in(frame, pa, pb, input.penalty, omit, input.clip_first) {
            Bounded::Negligible(bound) => {
                *negligible_bound = Some(bound);
                return None;
            }
            Bounded::Contact(c) => c,
        }
    } else {
        tet_tet_contact(pa, pb, input.penalty)
    };
    let centre = contact.centre?;
    let (mut fa, mut fb) = (contact.on_a, contact.on_b);
    let key = spring_key(a, b);
    let full = fb.iter().sum::<Vec3>().norm();
    // A pair newly allowed to touch that overlaps starts overlapped; it is
    // followed (with its offset) until it separates.
    let fresh = input.fresh && (full > 0.0 || fa.iter().any(|f| *f != Vec3::zeros()));
    let offset = match input.activation {
        Activation::Offset => true,
        Activation::Couple => !input.couple,
        Activation::Paper | Activation::Ramp => false,
        // A couple with no ramp to settle over starts at full force.
        Activation::Settle => !(input.couple && input.n_total == 0.0),
    };
    let mut started =
        if fresh { Some(if offset { full } else { 0.0 }) } else { input.started.get(&key).map(|&off| off.min(full)) };
    let ramp = input.ramps.get(&key).copied();
    if input.activation == Activation::Settle
        && let (Some(off), Some(n_c)) = (started.as_mut(), ramp)
        && n_c > 0
    {
        // The couple's offset shrinks to zero over the Eq. 18 steps:
        // `N_off = N₀ (1 − n_c / n_total)` (from the stored value, whose
        // last step had `n_c − 1`).
        let left = input.n_total - Real::from(n_c);
        *off *= (left / (left + 1.0)).max(0.0);
    }
    // Eq. 18's `n_c / n_total` while the ramp lasts (from 0 for a pair that
    // starts now with `Activation::Ramp`), else 1; with an offset, the share
    // of the resultant beyond it.
    let mut scale = if fresh && input.activation == Activation::Ramp && input.n_total > 0.0 {
        0.0
    } else if input.activation == Activation::Settle {
        1.0 // the ramp acts on the offset
    } else {
        ramp.map_or(1.0, |n_c| Real::from(n_c) / input.n_total)
    };
    if let Some(off) = started.filter(|&off| off > 0.0) {
        scale *= if full > off { 1.0 - off / full } else { 0.0 };
    }
    if scale != 1.0 {
        for f in fa.iter_mut().chain(fb.iter_mut()) {
            *f *= scale;
        }
    }
    let normal: Vec3 = fb.iter().sum();
    let n_mag = normal.norm();
    if n_mag == 0.0 && fa.iter().all(|f| f.norm() == 0.0) && started.is_none() {
        return None;
    }
    let mut out = PairForce {
        tets: input.tets,
        normal: [fa, fb],
        friction: Vec3::zeros(),
        weights: [[0.25; 4]; 2],
        spring: Vec3::zeros(),
        spring_energy: 0.0,
        energy: energy * scale,
        started,
        fresh,
        exact: input.model == ContactModel::Gradient && scale == 1.0 && started.is_none(),
        kick: [[Vec3::zeros(); 4]; 2],
        touching: true,
        onset: None,
    };
    let mu = input.friction.get(input.regions[a as usize], input.regions[b as usize]);
    if mu > 0.0 && n_mag > 0.0 {
        let n = normal / n_mag;
        let weights = [pa, pb].map(|p| barycentric(p, &centre).unwrap_or([0.25; 4]));
        let at =
            |side: usize| -> Vec3 { (0..4).map(|k| input.v[input.nodes[side][k] as usize] * weights[side][k]).sum() };
        let rel = at(1) - at(0);
        let vt = rel - n * rel.dot(&n);
        // Springs are stored as (larger index) relative to (smaller index).
        let sign = if a < b { 1.0 } else { -1.0 };
        let mut spring = input.spring * sign;
        spring -= n * spring.dot(&n);
        spring += vt * input.dt;
        let kt = input.penalty * input.size;
        let limit = mu * n_mag;
        let mut ft = -spring * kt;
        if ft.norm() > limit {
            ft *= limit / ft.norm();
            spring = -ft / kt;
        }
        out.friction = ft;
        out.weights = weights;
        out.spring = spring * sign;
        out.spring_energy = 0.5 * kt * spring.norm_squared();
    }
    Some(out)
}
