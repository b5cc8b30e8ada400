//! Full detection: when the candidates must be found again (the buffer
//! criterion) and the NBS pass over the bounding spheres of the contactable
//! tets that finds them (`Contact::detect`); additions after joint
//! failures are `incremental.rs`'s.

use femdem_contact::separated_by_face_plane;
use femdem_core::{Real, Vec3};
use rayon::prelude::*;

use super::Contact;
use crate::model::Model;

/// What the candidates need before a pass's pair loop
/// (`Contact::needs_detection`).
pub(super) enum Update {
    /// Nothing: they hold every pair that can touch.
    None,
    /// A full detection (`Contact::detect`).
    Full,
    /// The pairs of the pending tets (`Contact::add_candidates`); every
    /// watched node is at most `moved` (m) from its reference position.
    Add { moved: Real },
}

impl Contact {
    /// The bounding spheres of the contactable tets at positions `x` into
    /// `centers` and `radii` (indexed as `list`): centroid and largest
    /// distance to a node.
    pub(super) fn spheres(&mut self, model: &Model, x: &[Vec3]) {
        self.centers.clear();
        self.radii.clear();
        for &t in &self.list {
            let p = model.tets[t as usize].map(|n| x[n as usize]);
            let c = (p[0] + p[1] + p[2] + p[3]) / 4.0;
            let r = p.iter().map(|q| (q - c).norm()).fold(0.0, Real::max);
            self.centers.push(c);
            self.radii.push(r);
        }
    }

    /// Runs NBS over the contactable tets at positions `x` with margin
    /// `b/2`, keeping the pairs that may touch as the candidates; every
    /// contactable node's reference position becomes its position now. Not
    /// inlined, so that a profile names it.
    #[inline(never)]
    pub(super) fn detect(&mut self, model: &Model, x: &[Vec3]) {
        self.spheres(model, x);
        self.pairs.clear();
        self.nbs.detect(&self.centers, &self.radii, 0.5 * self.settings.buffer, &mut self.pairs);
        // A canonical order, ascending `(a, b)`: the forces are then summed
        // in the same order whatever the buffer (which changes NBS's grid and
        // so its order). `list` is ascending, so this is the order of the
        // sphere indices `(i, j)`, `i < j`: a counting sort by `i` into
        // `by_first`, then each `i`'s partners sorted (a handful each), in
        // O(pairs) rather than a comparison sort of all of them (which was
        // 17% of a fragmented step).
        let n = self.list.len();
        self.first.clear();
        self.first.resize(n + 1, 0);
        for p in &self.pairs {
            self.first[p.a() as usize + 1] += 1;
        }
        for i in 0..n {
            self.first[i + 1] += self.first[i];
        }
        self.by_first.clear();
        self.by_first.resize(self.pairs.len(), 0);
        let mut fill = std::mem::take(&mut self.fill);
        fill.clear();
        fill.extend_from_slice(&self.first[..n]);
        for p in &self.pairs {
            let slot = &mut fill[p.a() as usize];
            self.by_first[*slot as usize] = p.b();
            *slot += 1;
        }
        self.fill = fill;
        let mut candidates = std::mem::take(&mut self.candidates);
        candidates.clear();
        for i in 0..n {
            self.by_first[self.first[i] as usize..self.first[i + 1] as usize].sort_unstable();
        }
        // Pairs a face plane keeps more than the buffer apart cannot touch
        // before the next detection (`separated_by_face_plane`): dropping
        // them changes no force, and most sphere pairs of a mesh with
        // pre-existing fractures are such neighbours a layer apart.
        let gap = self.settings.buffer;
        for i in 0..n {
            let a = self.list[i];
            let pa = model.tets[a as usize].map(|k| x[k as usize]);
            for &j in &self.by_first[self.first[i] as usize..self.first[i + 1] as usize] {
                let b = self.list[j as usize];
                if self.may_touch(model, a, b)
                    && !separated_by_face_plane(&pa, &model.tets[b as usize].map(|k| x[k as usize]), gap)
                {
                    candidates.push((a, b));
                }
            }
        }
        self.candidates = candidates;
        if self.stale || !self.pending.is_empty() {
            self.nodes.clear();
            self.nodes.extend(self.list.iter().flat_map(|&t| model.tets[t as usize]));
            self.nodes.sort_unstable();
            self.nodes.dedup();
        }
        self.x_ref.clear();
        self.x_ref.extend(self.nodes.iter().map(|&n| x[n as usize]));
        self.certificates.cache(&self.candidates);
        self.stale = false;
        self.pending.clear();
        self.detections += 1;
    }

    /// What the candidates need before the pair loop at positions `x`: a
    /// full detection when one is stale or a contactable node moved more
    /// than `b/2` from its reference position, else the pairs of the
    /// pending tets, if any (a full detection too when
    /// [`ContactSettings::incremental`] is off).
    ///
    /// Why `b/2` suffices: let `d` bound every node's move. A point `q` in
    /// both tets now is a convex combination of each tet's current nodes;
    /// the same combination of the nodes at detection lies in that tet then,
    /// within `d` of `q`, so `|c_A − c_B| ≤ r_A + r_B + 2d` for the centres
    /// and radii at detection, and NBS with margin `b/2` kept every pair with
    /// `|c_A − c_B| ≤ r_A + r_B + b`. (The comparison is strict, so `b = 0`
    /// detects again whenever anything moved.) An addition keeps the same
    /// guarantee with a larger margin (`incremental.rs`).
    pub(super) fn needs_detection(&self, x: &[Vec3]) -> Update {
        if self.stale || (!self.pending.is_empty() && !self.settings.incremental) {
            return Update::Full;
        }
        let half = 0.5 * self.settings.buffer;
        let limit = half * half;
        let moved2 = |(&n, r): (&u32, &Vec3)| (x[n as usize] - r).norm_squared();
        if self.pending.is_empty() {
            let far = self.nodes.par_iter().zip(&self.x_ref).any(|p| moved2(p) > limit);
            return if far { Update::Full } else { Update::None };
        }
        // The largest move (a maximum: the same whatever the thread count).
        let largest = self.nodes.par_iter().zip(&self.x_ref).map(moved2).reduce(|| 0.0, Real::max);
        if largest > limit { Update::Full } else { Update::Add { moved: largest.sqrt() } }
    }
}
