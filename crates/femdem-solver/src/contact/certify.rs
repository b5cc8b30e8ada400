//! Negligible pairs certified over many steps: a candidate pair whose
//! Eq. 17 forces are provably negligible near a configuration is skipped,
//! without bounding it again, while its nodes stay (relative to one
//! another) within the radius it was certified for.
//!
//! **Why.** In a fracture network most candidate pairs are tets that meet
//! only at a vertex across a fracture; their forces are of third order in
//! the overlap, and `femdem_contact::contact_bound` proves them negligible
//! ([`super::ContactSettings::negligible`]) — at every step again, which
//! cost as much as the clipping of the pairs that do carry force
//! (`docs/performance.md`). Their nodes move by a small fraction of a tet
//! size over many steps.
//!
//! **How.** Each node of a contactable tet has an *anchor* position, and
//! the anchors of a pair's eight nodes are a configuration `X` (any
//! configuration: the anchors need not date from one step). When the bound
//! shows an overlapping pair (bound `> 0`) negligible at a pass and the
//! pair holds no certificate valid there, it is certified: with `D` the
//! deviation of its nodes from `X` now (below), the radius `δ = D + δ₀` is
//! certified when `D ≤ δ₀` and [`contact_bound_near`]`(X, δ)` passes the
//! same test as the bound (`δ₀ = ℓ ν^{1/3} / 32`; `ℓ` the smaller tet's
//! `V^{1/3}`, `ν` the `negligible` setting: the bound of a vertex contact
//! grows as the cube of the radius, so `δ₀³ / ℓ` stays below `ν ℓ²` up to
//! the bound's constant factors); otherwise the pair is marked *bounded*
//! (bounded at every pass) until the next epoch. Why these two choices
//! (measured, `docs/performance.md`): a first try at `ℓ ν^{1/3} / 4`
//! passed for no pair at all on the multi-layer and README runs (0 of
//! 190,676 at an epoch's start on the first, 0 of 42,848 on the second),
//! one eighth of it for 48–80%; and a lapsed certificate (`D` above its
//! old radius, so above `δ₀`) asks for a radius more than twice `δ₀`, whose
//! bound is some eight times larger: 7% passed, not worth the try.
//!
//! At every pass a pair whose deviation is at most its radius is skipped:
//! its forces are below `p` times the bound near `X`
//! (`femdem_contact::bound_near`'s module documentation), so below the
//! threshold, for every configuration within the radius — the decision
//! depends on the positions of the pass alone, not on the path there.
//!
//! *The deviation* of positions `x` from `X` is `max_k |u_k − ū|` over the
//! eight nodes, `u_k = x_k − X_k` and `ū` their mean: the pair is within it
//! of `X` after the common translation `ū`, which changes no force. It is
//! computed to a few ulps of the coordinates, which the bound's slack (at
//! least 10⁻⁹ of a height and 10³ ulps of the coordinates over a height)
//! covers.
//!
//! **Epochs.** The first pass anchors the nodes of every contactable tet
//! where they are; a tet made contactable later has its nodes not yet
//! anchored anchored at the next pass. A new epoch — every contactable node
//! anchored again, every certificate forgotten — begins at a pass once the
//! last one bounded more overlapping negligible pairs in full than a
//! quarter ([`RENEW`]) of the certificates, and the epoch is at least
//! [`MIN_AGE`] passes old.
//!
//! **What it changes, and what not.** A certified pair is skipped where the
//! bound at the pass might not have shown it negligible (the bound near `X`
//! is not an upper bound on the bound here), so forces below the threshold
//! can be dropped that the bound alone would have added: the results move
//! within what `negligible` allows, not bit for bit. They depend neither on
//! the thread count nor on the detection buffer or incremental detection:
//! certificates are kept per pair, whether or not it is a candidate, and
//! change only at passes where the pair overlaps (so is a candidate
//! whatever the detection); the epoch's counts count such pairs only; the
//! anchors follow the contactable set. A checkpoint holds them all.

use femdem_contact::contact_bound_near;
use femdem_core::{Real, Vec3};

use super::pair::PairMap;

/// A pair with no certificate.
pub(super) const UNTRIED: Real = 0.0;
/// A pair that could not be certified at this epoch: bounded at every pass
/// until the next.
pub(super) const BOUNDED: Real = -1.0;
/// Passes an epoch lasts at least.
pub(super) const MIN_AGE: u32 = 8;
/// An epoch is renewed once the pairs bounded in full at a pass exceed
/// `1 / RENEW` of the certificates (4: measured on the multi-layer case,
/// 1.07× faster than 1 and 1.05× than 16, `docs/performance.md`).
pub(super) const RENEW: u64 = 4;

/// The certificates of the pairs and the anchors of the nodes.
#[derive(Clone, Debug, Default)]
pub(super) struct Certificates {
    /// Per pair: the radius `δ` it is certified for (`> 0`) or [`BOUNDED`].
    pub map: PairMap<Real>,
    /// `map`'s value for each candidate (in the candidates' order), or
    /// [`UNTRIED`].
    pub cached: Vec<Real>,
    /// Anchor position per node (read where `anchored`), m.
    pub anchor: Vec<Vec3>,
    pub anchored: Vec<bool>,
    /// Tets made contactable whose nodes are to be anchored at the next
    /// pass.
    pub to_anchor: Vec<u32>,
    /// Passes since the epoch began.
    pub age: u32,
    /// Overlapping pairs shown negligible by the bound in full at the last
    /// pass.
    pub bounded: u64,
    /// Pairs holding a certificate (the entries of `map` above zero).
    pub certified: u64,
}

/// What one pair's evaluation did with certificates.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Verdict {
    /// Skipped: within its certificate's radius.
    pub skipped: bool,
    /// An overlapping pair the bound showed negligible (not skipped).
    pub bounded: bool,
    /// Its new certificate (radius or [`BOUNDED`]), if it changed.
    pub update: Option<Real>,
}

impl Certificates {
    /// A new epoch: the nodes of the tets `list` (of `tets`) anchored at
    /// their positions in `x`, every certificate forgotten.
    pub fn renew(&mut self, tets: &[[u32; 4]], list: &[u32], x: &[Vec3]) {
        self.anchor.resize(x.len(), Vec3::zeros());
        self.anchored.clear();
        self.anchored.resize(x.len(), false);
        for &t in list {
            for n in tets[t as usize] {
                self.anchor[n as usize] = x[n as usize];
                self.anchored[n as usize] = true;
            }
        }
        self.to_anchor.clear();
        self.map.clear();
        self.cached.fill(UNTRIED);
        self.age = 0;
        self.bounded = 0;
        self.certified = 0;
    }

    /// Anchors the nodes of [`Certificates::to_anchor`]'s tets not yet
    /// anchored at their positions in `x` (none before the first epoch).
    pub fn anchor_new(&mut self, tets: &[[u32; 4]], x: &[Vec3]) {
        for &t in &self.to_anchor {
            for n in tets[t as usize] {
                if let Some(done) = self.anchored.get_mut(n as usize)
                    && !*done
                {
                    self.anchor[n as usize] = x[n as usize];
                    *done = true;
                }
            }
        }
        self.to_anchor.clear();
    }

    /// [`Certificates::cached`] for the candidates `candidates`.
    pub fn cache(&mut self, candidates: &[(u32, u32)]) {
        self.cached.clear();
        self.cached.extend(candidates.iter().map(|p| self.map.get(p).copied().unwrap_or(UNTRIED)));
    }

    /// Whether this pass begins a new epoch: at the first, then as the
    /// module documentation says.
    pub fn stale(&self) -> bool {
        self.anchored.is_empty() || (self.age >= MIN_AGE && RENEW * self.bounded > self.certified)
    }

    /// Counts the pairs holding a certificate (after `map` was read back).
    pub fn count_certified(&mut self) {
        self.certified = self.map.values().filter(|&&r| r > 0.0).count() as u64;
    }

    /// Books a pass's verdicts on `candidates` (in their order).
    pub fn book(&mut self, candidates: &[(u32, u32)], verdicts: impl Iterator<Item = Verdict>) {
        self.bounded = 0;
        for (i, v) in verdicts.enumerate() {
            self.bounded += u64::from(v.bounded);
            if let Some(r) = v.update {
                let old = self.map.insert(candidates[i], r).unwrap_or(UNTRIED);
                self.certified = self.certified + u64::from(r > 0.0) - u64::from(old > 0.0);
                self.cached[i] = r;
            }
        }
        self.age = self.age.saturating_add(1);
    }
}

/// A tet's nodes' displacement from their anchors, summarised: `mean` is
/// `m = ¼ Σ_k u_k` and `spread` `r = max_k |u_k − m|` over its four nodes
/// (`u_k = x_k − X_k`, m).
///
/// For a pair of tets `a`, `b` the mean of the eight is `ū = ½ (m_a + m_b)`,
/// so each node's `|u_k − ū| ≤ |u_k − m_s| + |m_s − ū|`: the pair's
/// [`deviation`] is at most `max(r_a, r_b) + ½ |m_a − m_b|`
/// ([`Drift::surely_within`]). A certified pair whose bound is within its
/// radius is skipped from these two summaries, without reading its eight
/// nodes and their anchors; the others are decided by the deviation
/// itself, so the decisions are those of the deviation alone.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Drift {
    mean: Vec3,
    spread: Real,
}

impl Drift {
    /// The summary of tet `nodes` at positions `x` with anchors `anchor`.
    pub fn of(nodes: &[u32; 4], x: &[Vec3], anchor: &[Vec3]) -> Drift {
        let u = nodes.map(|n| x[n as usize] - anchor[n as usize]);
        let mean = (u[0] + u[1] + u[2] + u[3]) / 4.0;
        let spread = u.iter().map(|uk| (uk - mean).norm_squared()).fold(0.0, Real::max).sqrt();
        Drift { mean, spread }
    }

    /// Whether the [`deviation`] of the pair of tets summarised by `self`
    /// and `other` is surely at most `radius`, as computed: their bound
    /// (the type's documentation) with a margin of `10⁻¹³` of the
    /// displacements' size, far above the rounding of the two
    /// computations (a few ulps of the displacements each), so that this
    /// answers yes only where [`deviation`] would.
    pub fn surely_within(&self, other: &Drift, radius: Real) -> bool {
        let bound = self.spread.max(other.spread) + 0.5 * (self.mean - other.mean).norm();
        let size = self.mean.norm() + other.mean.norm() + self.spread + other.spread;
        bound + 1e-13 * (size + bound) <= radius
    }
}

/// The anchors of tets `nodes` (a pair's) from `anchor`.
pub(super) fn anchors(anchor: &[Vec3], nodes: &[[u32; 4]; 2]) -> [[Vec3; 4]; 2] {
    nodes.map(|t| t.map(|n| anchor[n as usize]))
}

/// The deviation of positions `x` from anchors `at` (the module
/// documentation), m.
#[inline(always)]
pub(super) fn deviation(x: &[[Vec3; 4]; 2], at: &[[Vec3; 4]; 2]) -> Real {
    let mut mean = Vec3::zeros();
    for s in 0..2 {
        for k in 0..4 {
            mean += x[s][k] - at[s][k];
        }
    }
    mean /= 8.0;
    let mut worst: Real = 0.0;
    for s in 0..2 {
        for k in 0..4 {
            worst = worst.max((x[s][k] - at[s][k] - mean).norm_squared());
        }
    }
    worst.sqrt()
}

/// The radius a pair negligible now is certified for around its anchors
/// `at`, from which its positions deviate by `d` ([`deviation`]): `d + δ₀`
/// where `d ≤ δ₀` and the bound near `at` passes `negligible` (the module
/// documentation), else [`BOUNDED`]. `volume` is the smaller tet's
/// reference volume, m³.
pub(super) fn certify(at: &[[Vec3; 4]; 2], d: Real, volume: Real, negligible: Real) -> Real {
    let delta0 = volume.cbrt() * negligible.cbrt() / 32.0;
    // (A deviation that is not a number certifies nothing.)
    if d.is_nan() || d > delta0 {
        return BOUNDED;
    }
    let delta = d + delta0;
    let r = contact_bound_near(&at[0], &at[1], delta) / negligible;
    // At most `ν ℓ²`, as cubes (`pair::evaluate` compares `bound ≤ ν ℓ²`
    // with the kept `ℓ = V^{1/3}`: the same test but for rounding at the
    // threshold itself).
    if r * r * r <= volume * volume { delta } else { BOUNDED }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A common translation is no deviation; one node moved by `d` deviates
    /// by `7/8 d` from the mean of the eight.
    #[test]
    fn the_deviation_ignores_a_common_translation() {
        let at: [[Vec3; 4]; 2] =
            std::array::from_fn(|s| std::array::from_fn(|k| Vec3::new(k as f64, s as f64, (k * s) as f64)));
        let shift = Vec3::new(0.3, -2.0, 1e3);
        let moved = at.map(|t| t.map(|p| p + shift));
        assert!(deviation(&moved, &at) < 1e-12);
        let mut one = at;
        one[1][2] += Vec3::new(0.0, 0.0, 1e-3);
        assert!((deviation(&one, &at) - 7e-3 / 8.0).abs() < 1e-15);
    }

    /// The two tets' summaries bound the pair's deviation (random
    /// displacements of one tet or both, at three scales, on top of a
    /// common shift); where `surely_within` says yes, `deviation` is within
    /// the radius; and for two tets that only translate, by different
    /// vectors and with no common shift, the bound is the deviation itself,
    /// so a radius above it by 10⁻⁹ is surely within.
    #[test]
    fn the_drifts_bound_the_deviation() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let nodes = [[0, 1, 2, 3], [4, 5, 6, 7]];
        for case in 0..3000 {
            let at: Vec<Vec3> =
                (0..8).map(|_| Vec3::new(next(), next(), next()) * 0.05 + Vec3::new(1.5, -2.0, 0.7)).collect();
            let rigid = case % 4 == 3;
            // (Rigid motions large against the coordinates' rounding.)
            let scale = if rigid { 1e-3 } else { [1e-9, 1e-6, 1e-3][case % 3] };
            // (The margin grows with a common shift, as the rounding does.)
            let shift = if rigid { Vec3::zeros() } else { Vec3::new(next(), next(), next()) * 1e-2 };
            let moves = [Vec3::new(next(), next(), next()) * scale, Vec3::new(next(), next(), next()) * scale];
            let x: Vec<Vec3> = (0..8)
                .map(|k| {
                    let own = if rigid {
                        moves[k / 4]
                    } else if case % 4 == 0 || k < 4 {
                        Vec3::new(next(), next(), next()) * scale
                    } else {
                        Vec3::zeros()
                    };
                    at[k] + shift + own
                })
                .collect();
            let xs = nodes.map(|t| t.map(|n| x[n as usize]));
            let ats = nodes.map(|t| t.map(|n| at[n as usize]));
            let d = deviation(&xs, &ats);
            let [da, db] = nodes.map(|t| Drift::of(&t, &x, &at));
            for radius in [d * (1.0 - 1e-12), d, d * (1.0 + 1e-9), d * 1.5, d * 3.0] {
                if da.surely_within(&db, radius) {
                    assert!(d <= radius, "case {case}: said within {radius:e}, deviation {d:e}");
                }
            }
            if rigid {
                assert!(da.surely_within(&db, d * (1.0 + 1e-9)), "case {case}: rigid motions, deviation {d:e}");
            }
        }
    }

    /// A new epoch anchors the contactable tets' nodes and forgets every
    /// certificate; tets made contactable later are anchored once, where
    /// they are at the next pass; the epoch is stale once the overlapping
    /// pairs bounded at a pass exceed a quarter (`RENEW`) of the
    /// certificates, and not before `MIN_AGE` passes.
    #[test]
    fn epochs_anchor_the_contactable_nodes_and_forget_certificates() {
        let tets = [[0, 1, 2, 3], [4, 5, 6, 7]];
        let x: Vec<Vec3> = (0..8).map(|k| Vec3::new(k as f64, 0.0, 0.0)).collect();
        let mut c = Certificates::default();
        assert!(c.stale(), "no epoch yet");
        c.renew(&tets, &[0], &x);
        assert_eq!((c.anchored[3], c.anchored[4], c.anchor[3]), (true, false, x[3]));
        let y: Vec<Vec3> = x.iter().map(|p| p * 2.0).collect();
        c.to_anchor = vec![0, 1];
        c.anchor_new(&tets, &y);
        assert_eq!((c.anchor[3], c.anchor[4]), (x[3], y[4]), "anchored once");
        let pairs = [(0, 1), (2, 3)];
        c.cache(&pairs);
        let bounded = Verdict { bounded: true, ..Verdict::default() };
        let certified = Verdict { update: Some(1e-6), ..Verdict::default() };
        c.book(&pairs, [certified, bounded].into_iter());
        assert_eq!((c.map[&(0, 1)], c.cached.as_slice(), c.certified), (1e-6, [1e-6, UNTRIED].as_slice(), 1));
        c.count_certified();
        assert_eq!(c.certified, 1);
        for pass in 2..=MIN_AGE {
            // Nothing bounded against one certificate: not stale; one
            // bounded is more than a quarter of it: stale once old enough.
            c.book(&pairs, [Verdict::default(), Verdict::default()].into_iter());
            assert!(!c.stale(), "pass {pass}");
        }
        c.book(&pairs, [Verdict::default(), bounded].into_iter());
        assert!(c.stale());
        c.renew(&tets, &[0, 1], &y);
        assert_eq!((c.map.len(), c.cached.as_slice(), c.age, c.anchor[3]), (0, [UNTRIED; 2].as_slice(), 0, y[3]));
    }
}
