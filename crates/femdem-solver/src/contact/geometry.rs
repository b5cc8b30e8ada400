//! The candidate pairs' Eq. 17 contacts computed elsewhere than in the
//! pass — on a device, `femdem_gpu::Bulk::pair_geometry` — for
//! [`Contact::pass_with`]: which pairs the pass asks for, and what it costs.
//!
//! Only the pairs the pass would clip are asked for: a pair within its
//! certificate's radius is skipped before its geometry is looked at, and a
//! pair whose bounding boxes are apart has no contact (`pair::evaluate`'s
//! first test), so neither is sent. The same two tests, on the same
//! numbers, run again in the pass, so the pairs it looks up are exactly
//! those asked for.

use femdem_contact::Bounded;
use femdem_core::{Real, Vec3};
use rayon::prelude::*;

use super::pair::boxes_overlap;
use super::{Contact, ContactModel, certify};
use crate::model::Model;

/// Where [`Contact::pass_with`] gets the candidate pairs' Eq. 17 contacts:
/// given the pairs, their `negligible` thresholds (m², where the settings
/// have one), the penalty (Pa) and an empty vector (whose memory the last
/// pass used), it pushes one result per pair and returns `true`, or
/// returns `false` to have them computed on the CPU after all.
pub(crate) type Geometry<'a> = dyn FnMut(&[[u32; 2]], Option<&[Real]>, Real, &mut Vec<Bounded>) -> bool + 'a;

/// A candidate not asked for.
const NOT_ASKED: u32 = u32::MAX;

/// The contacts a geometry gave for the candidates that were asked for.
/// Its vectors are handed back to the next pass ([`Contact::keep_asked`]):
/// at the paper's multi-layer size they hold some 10⁵ pairs, and fresh
/// ones every step cost more than the device's copy (`docs/performance.md`).
#[derive(Default)]
pub(crate) struct Asked {
    /// Per candidate, its place in `found`, or [`NOT_ASKED`].
    slot: Vec<u32>,
    found: Vec<Bounded>,
    /// The pairs asked for and their thresholds, kept for their memory.
    pairs: Vec<[u32; 2]>,
    omits: Vec<Real>,
}

/// A copy starts empty: the vectors are scratch memory between passes.
impl Clone for Asked {
    fn clone(&self) -> Self {
        Asked::default()
    }
}

impl std::fmt::Debug for Asked {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Asked").field("pairs", &self.pairs.len()).finish_non_exhaustive()
    }
}

impl Asked {
    /// Candidate `k`'s contact, where it was asked for.
    pub fn get(&self, k: usize) -> Option<Bounded> {
        let s = self.slot[k];
        (s != NOT_ASKED).then(|| self.found[s as usize])
    }
}

impl Contact {
    /// Whether [`Contact::pass_with`] asks its geometry for the pairs'
    /// contacts: with the potential model (the gradient one is the CPU's).
    pub(crate) fn geometry_elsewhere(&self) -> bool {
        self.settings.model == ContactModel::Potential
    }

    /// Bytes the last pass with [`Contact::pass_with`] moved to and from a
    /// device for its geometry: per pair asked for and answered, 8 up (and
    /// 8 for its threshold where `negligible` is set) and 240 back (0 where
    /// the device could not answer and the CPU clipped).
    pub(crate) fn geometry_bytes(&self) -> usize {
        if !self.geometry_elsewhere() {
            return 0;
        }
        let up = if self.settings.negligible > 0.0 { 16 } else { 8 };
        self.asked * (up + 240)
    }

    /// The contacts from `geometry` of the candidates the pass will clip at
    /// positions `x` (the module documentation), where the model's are
    /// computed elsewhere and there are such pairs; each pair's threshold
    /// as `pair::evaluate` forms it, `negligible · ℓ²`. Called after the
    /// certificates are renewed or anchored, as the pass reads them.
    pub(super) fn ask_geometry(&mut self, model: &Model, x: &[Vec3], geometry: &mut Geometry<'_>) -> Option<Asked> {
        self.asked = 0;
        if !self.geometry_elsewhere() || self.candidates.is_empty() {
            return None;
        }
        let certifying = self.certifying();
        let (anchor, drifts) = (&self.certificates.anchor, &self.drifts);
        let newly = self.newly.any().then_some(&self.newly);
        let clipped: Vec<bool> = self
            .candidates
            .par_iter()
            .zip(self.certificates.cached.par_iter())
            .map(|(&(a, b), &radius)| {
                let fresh = newly.is_some_and(|n| n.contains(a, b));
                let certified = certifying && radius > 0.0 && !fresh;
                // The pass's own decision: surely within by the drifts, else
                // by the deviation.
                if certified && drifts[a as usize].surely_within(&drifts[b as usize], radius) {
                    return false;
                }
                let nodes = [model.tets[a as usize], model.tets[b as usize]];
                let xs = nodes.map(|t| t.map(|n| x[n as usize]));
                let skipped = certified && certify::deviation(&xs, &certify::anchors(anchor, &nodes)) <= radius;
                !skipped && boxes_overlap(&xs[0], &xs[1])
            })
            .collect();
        let mut asked = std::mem::take(&mut self.asked_memory);
        let Asked { slot, found, pairs, omits } = &mut asked;
        slot.clear();
        slot.resize(self.candidates.len(), NOT_ASKED);
        pairs.clear();
        for (k, (&(a, b), _)) in self.candidates.iter().zip(&clipped).enumerate().filter(|(_, (_, c))| **c) {
            slot[k] = u32::try_from(pairs.len()).expect("fewer than 2^32 pairs");
            pairs.push([a, b]);
        }
        if pairs.is_empty() {
            self.asked_memory = asked;
            return None;
        }
        let (negligible, sizes) = (self.settings.negligible, &self.sizes);
        let omit = |&[a, b]: &[u32; 2]| negligible * sizes[a as usize].min(sizes[b as usize]).powi(2);
        omits.clear();
        if negligible > 0.0 {
            omits.extend(pairs.iter().map(omit));
        }
        found.clear();
        let thresholds = (negligible > 0.0).then_some(&omits[..]);
        if !geometry(pairs, thresholds, self.settings.penalty, found) {
            self.asked_memory = asked;
            return None;
        }
        assert_eq!(found.len(), pairs.len(), "the geometry answers every pair it was asked for");
        self.asked = pairs.len();
        Some(asked)
    }

    /// Keeps the vectors of the pass's `Asked` for the next pass.
    pub(super) fn keep_asked(&mut self, asked: Option<Asked>) {
        if let Some(a) = asked {
            self.asked_memory = a;
        }
    }
}
