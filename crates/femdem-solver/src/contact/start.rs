//! Which pairs are *newly allowed* to touch at a pass, so that one that
//! already overlaps there starts as [`super::Activation`] says.
//!
//! A pair that was allowed to touch before cannot be found overlapping for
//! the first time other than by approaching, and approaching contacts start
//! at zero overlap in the limit of small steps; whether such a pair was a
//! candidate at the pass before depends on when detection ran (the
//! buffer), so candidate-list membership cannot be the test (results must
//! not depend on the buffer). What changes whether a pair may touch is a
//! crack (`Contact::crack`, for a failed joint or a pre-existing fracture
//! face) and the start of the scene:
//!
//! * at the first pass every pair is newly allowed;
//! * a tet made contactable by a crack may touch every other contactable
//!   tet it did not before;
//! * among the tets around a cracked vertex (the stars of Eq. 15), a pair
//!   may touch once the crack separates it there or unbonds it (its joint
//!   failed): `may_touch` is evaluated for the pairs of each star before
//!   and after the crack, and those that flip from no to yes are recorded.
//!
//! No other pair's `may_touch` changes (a pair that shares no cracked
//! vertex is decided by contactability alone, and only the cracked
//! vertices' pieces are found again). The sets are consumed by the next
//! pass and are the same whatever the buffer and the thread count.

use super::{Contact, spring_key};
use crate::model::Model;

/// What a crack newly allows, until the next pass reads it.
#[derive(Clone, Debug, Default)]
pub(super) struct NewlyAllowed {
    /// Whether the next pass is the first (everything is new).
    pub first: bool,
    /// Per tet: made contactable since the last pass.
    pub contactable: Vec<bool>,
    /// Those tets, to clear the flags.
    pub tets: Vec<u32>,
    /// Pairs of star tets that may touch since the last pass and could not
    /// before (keys as `spring_key`, ascending once `settle` has run).
    pub pairs: Vec<(u32, u32)>,
    /// The couples (Eq. 14) of the joints that failed in compression since
    /// the last pass (keys as `spring_key`, ascending once `settle` has
    /// run): with `Activation::Couple` (and, settling, `Activation::Settle`) they start as with
    /// `Activation::Paper` (Eq. 18, or at once with `ramp_steps = 0`).
    pub couples: Vec<(u32, u32)>,
}

impl NewlyAllowed {
    /// Nothing new yet, for a model of `n_tets` tets, before the first pass.
    pub fn new(n_tets: usize) -> NewlyAllowed {
        NewlyAllowed {
            first: true,
            contactable: vec![false; n_tets],
            tets: Vec::new(),
            pairs: Vec::new(),
            couples: Vec::new(),
        }
    }

    /// Whether anything is new at the next pass.
    pub fn any(&self) -> bool {
        self.first || !self.tets.is_empty() || !self.pairs.is_empty()
    }

    /// Sorts the pairs for [`NewlyAllowed::contains`].
    pub fn settle(&mut self) {
        self.pairs.sort_unstable();
        self.pairs.dedup();
        self.couples.sort_unstable();
        self.couples.dedup();
    }

    /// Whether `(a, b)` is the couple of a joint that failed since the last
    /// pass.
    pub fn is_couple(&self, a: u32, b: u32) -> bool {
        self.couples.binary_search(&spring_key(a, b)).is_ok()
    }

    /// Whether the pair `(a, b)` (`a < b`) is newly allowed.
    pub fn contains(&self, a: u32, b: u32) -> bool {
        self.first
            || self.contactable[a as usize]
            || self.contactable[b as usize]
            || self.pairs.binary_search(&spring_key(a, b)).is_ok()
    }

    /// Forgets what the pass has read.
    pub fn clear(&mut self) {
        self.first = false;
        for &t in &self.tets {
            self.contactable[t as usize] = false;
        }
        self.tets.clear();
        self.pairs.clear();
        self.couples.clear();
    }
}

impl Contact {
    /// The pairs within the stars of `vertices` that may touch now
    /// (contactable, and `may_touch`), as `spring_key`s.
    pub(super) fn allowed_in_stars(&self, model: &Model, vertices: &[u32]) -> Vec<(u32, u32)> {
        let mut allowed = Vec::new();
        for &v in vertices {
            let star = self.stars.of(v);
            for (i, &a) in star.iter().enumerate() {
                for &b in &star[i + 1..] {
                    if self.contactable[a as usize] && self.contactable[b as usize] && self.may_touch(model, a, b) {
                        allowed.push(spring_key(a, b));
                    }
                }
            }
        }
        allowed.sort_unstable();
        allowed.dedup();
        allowed
    }

    /// Records as newly allowed the pairs of the stars of `vertices` that
    /// may touch now and were not in `before` (ascending).
    pub(super) fn record_newly_allowed(&mut self, model: &Model, vertices: &[u32], before: &[(u32, u32)]) {
        let after = self.allowed_in_stars(model, vertices);
        let new = after.into_iter().filter(|p| before.binary_search(p).is_err());
        self.newly.pairs.extend(new);
    }

    /// Records tet `t` as made contactable since the last pass.
    pub(super) fn record_contactable(&mut self, t: u32) {
        if !self.newly.contactable[t as usize] {
            self.newly.contactable[t as usize] = true;
            self.newly.tets.push(t);
        }
    }
}
