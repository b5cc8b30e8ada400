//! One candidate pair of a contact pass: skipped within its certificate,
//! else evaluated (`pair::evaluate`), certified where the bound shows it
//! negligible; and the loop over all candidates, run through the widest
//! frame the processor has (`femdem_contact::Frame`, `widest.rs`).

use femdem_contact::{Frame, Plain};
use femdem_core::{Real, Vec3};
use rayon::prelude::*;

use super::certify::{self, Verdict};
use super::debts::corrected;
use super::geometry::Asked;
use super::onset;
use super::pair::{PairForce, PairInput, PairMap, evaluate};
use super::settings::{Activation, ContactModel, FrictionTable};
use super::start::NewlyAllowed;
use crate::model::Model;
use crate::widest::{VectorPath, Wide};

/// What every candidate of a pass reads.
pub(super) struct Candidates<'a> {
    pub model: &'a Model,
    pub x: &'a [Vec3],
    pub v: &'a [Vec3],
    pub dt: Real,
    /// Each tet's `ℓ = V^{1/3}`, m.
    pub sizes: &'a [Real],
    /// Whether certificates are kept (`certify.rs`), and their anchors and
    /// the tets' drifts from them.
    pub certifying: bool,
    pub anchor: &'a [Vec3],
    pub drifts: &'a [certify::Drift],
    /// The pairs newly allowed to touch at this pass, if any.
    pub newly: Option<&'a NewlyAllowed>,
    pub penalty: Real,
    pub n_total: Real,
    pub negligible: Real,
    pub activation: Activation,
    pub model_kind: ContactModel,
    pub friction: &'a FrictionTable,
    pub stick: &'a [((u32, u32), Vec3)],
    pub ramp: &'a PairMap<u32>,
    pub started: &'a PairMap<Real>,
    /// The pairs' contacts computed on a device, if asked for.
    pub precomputed: Option<&'a Asked>,
    /// With [`ContactModel::Gradient`]: the energy-consistent kicks'
    /// state (`onset.rs`).
    pub held: &'a PairMap<onset::Held>,
    pub primed: bool,
}

/// What the pass knows of one candidate: its index, its tets, its
/// certificate's radius (or `certify::UNTRIED`, `certify::BOUNDED`),
/// whether it was in contact at the last pass and its friction spring's
/// index in `stick` (out of range for none).
pub(super) type Candidate = (usize, (u32, u32), Real, bool, u32);

impl Candidates<'_> {
    /// Evaluates every candidate, in parallel, into `results` (in the
    /// candidates' order), the pair kernel compiled for the widest vector
    /// unit `path` allows (the same bits on every path: `frame.rs` of
    /// `femdem-contact`).
    pub fn evaluate_all(
        &self,
        path: VectorPath,
        candidates: impl IndexedParallelIterator<Item = Candidate>,
        results: &mut Vec<(Option<Box<PairForce>>, Verdict)>,
    ) {
        match Wide::new(path) {
            Some(wide) => self.run(wide, candidates, results),
            None => self.run(Plain, candidates, results),
        }
    }

    fn run<F: Frame>(
        &self,
        frame: F,
        candidates: impl IndexedParallelIterator<Item = Candidate>,
        results: &mut Vec<(Option<Box<PairForce>>, Verdict)>,
    ) {
        candidates
            .map(|c| {
                frame.call(
                    #[inline(always)]
                    |f| self.one(f, c),
                )
            })
            .collect_into_vec(results);
    }

    /// One candidate (the module documentation), in `frame`'s work.
    #[inline(always)]
    fn one<F: Frame>(
        &self,
        frame: F,
        (k, (a, b), radius, clip_first, spring): Candidate,
    ) -> (Option<Box<PairForce>>, Verdict) {
        let Candidates { model, x, certifying, drifts, newly, .. } = *self;
        let fresh = newly.is_some_and(|n| n.contains(a, b));
        let mut verdict = Verdict::default();
        // Within its certificate's radius: skipped (not a pair newly
        // allowed, whose start is decided at this pass); surely so by the
        // two tets' drifts, else by the deviation.
        let certified = certifying && radius > 0.0 && !fresh;
        if certified && drifts[a as usize].surely_within(&drifts[b as usize], radius) {
            verdict.skipped = true;
            return (None, verdict);
        }
        let (ta, tb) = (model.tets[a as usize], model.tets[b as usize]);
        let nodes = [ta, tb];
        let xs = [ta.map(|n| x[n as usize]), tb.map(|n| x[n as usize])];
        let size = self.sizes[a as usize].min(self.sizes[b as usize]);
        let at = || certify::anchors(self.anchor, &nodes);
        let deviation = certified.then(|| certify::deviation(&xs, &at()));
        if deviation.is_some_and(|d| d <= radius) {
            verdict.skipped = true;
            return (None, verdict);
        }
        let mut negligible_bound = None;
        let force = evaluate(
            frame,
            PairInput {
                tets: [a, b],
                x: xs,
                nodes,
                v: self.v,
                size,
                penalty: self.penalty,
                model: self.model_kind,
                negligible: self.negligible,
                clip_first,
                friction: self.friction,
                regions: &model.tet_region,
                ramps: self.ramp,
                n_total: self.n_total,
                spring: self.stick.get(spring as usize).map_or_else(Vec3::zeros, |s| s.1),
                dt: self.dt,
                fresh,
                couple: newly.is_some_and(|n| n.is_couple(a, b)),
                activation: self.activation,
                started: self.started,
                geometry: self.precomputed.and_then(|p| p.get(k)),
            },
            &mut negligible_bound,
        );
        let force = if self.model_kind == ContactModel::Gradient {
            corrected(force, [a, b], self.held, &xs, &nodes, self.v, self.dt, self.primed)
        } else {
            force
        };
        // An overlapping pair shown negligible: certified unless it is
        // marked bounded for this epoch.
        if certifying && negligible_bound.is_some_and(|b| b > 0.0) {
            verdict.bounded = true;
            if radius != certify::BOUNDED {
                // (Read here: most candidates never need it.)
                let volume = model.tet_ref[a as usize].volume.min(model.tet_ref[b as usize].volume);
                let at = at();
                // A lapsed pair's deviation is known already.
                let d = deviation.unwrap_or_else(|| certify::deviation(&xs, &at));
                verdict.update = Some(certify::certify(&at, d, volume, self.negligible));
            }
        }
        (force.map(Box::new), verdict)
    }
}
