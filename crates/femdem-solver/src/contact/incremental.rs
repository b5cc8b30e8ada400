//! Incremental detection: the candidate pairs a joint failure adds between
//! two full detections, so that a failure costs a search around the failed
//! joint instead of an NBS pass over every contactable tet.
//!
//! **What the candidates guarantee.** Every pair of contactable tets that
//! may touch (`Contact::may_touch`) and can overlap while every watched
//! node stays within `b/2` of its reference position is a candidate, except
//! pairs with a *pending* tet. A full detection makes it so (the references
//! are the positions then; see `Contact::needs_detection`), and a pass at
//! which some watched node is beyond `b/2` detects in full before its pair
//! loop, so at every pair loop each overlapping pair that may touch is a
//! candidate.
//!
//! **What a failure changes.** `Contact::crack` makes the tets around the
//! failed joint's three vertices contactable, unbonds the joint's two tets
//! (both around those vertices), and marks the vertices cracked with their
//! pieces found again. `may_touch(a, b)` reads the bonded set for `(a, b)`
//! and the pieces of the vertices `a` and `b` share; everything else it
//! reads (rigidity, shared nodes) is fixed. So a pair whose answer or
//! contactability changed has a tet around one of the three vertices: a
//! pending tet. And the answer only turns from false to true: the bonded
//! set only loses pairs, a star's pieces are found again with fewer links
//! (a finer partition), and a vertex is never uncracked. So the candidates
//! need no removal, only the pairs of the pending tets.
//!
//! **The margin of an addition.** At an addition every watched node is
//! within `D ≤ b/2` of its reference (else a full detection runs instead),
//! and stays within `b/2` until the next full detection: it moves at most
//! `m = b/2 + D` from here; a node first watched now takes its position
//! here as its reference and moves at most `b/2`. By the argument of
//! `Contact::needs_detection`, two tets that overlap before the next full
//! detection have bounding spheres here with `|c_A − c_B| ≤ r_A + r_B + 2m`,
//! and by `femdem_contact::separated_by_face_plane` a pair a face plane
//! separates by more than `2m` here has no force after moves of at most
//! `m`. So the pairs of each pending tet with every contactable tet, kept
//! when their spheres grown by `m` overlap, no face plane separates them by
//! `2m`, and they may touch, restore the guarantee.
//!
//! **Why the results are the same bit for bit.** The pair loop sums, in
//! candidate order, the pairs `pair::evaluate` finds overlapping (a contact
//! centre and a force); the others add nothing and leave no friction spring.
//! Candidates are kept ascending (the additions are merged in), and every
//! overlapping pair that may touch is one whether a full detection or an
//! addition found it, so the pairs summed and their order are those of a
//! full detection at every failure (`tests/solver/contact_incremental.rs`
//! compares the two). What an addition gives up is cost, not results: the
//! nodes watched before keep their references, so the next full detection
//! by the buffer can come sooner, and the margin is `D` wider.

use femdem_contact::separated_by_face_plane;
use femdem_core::{Real, Vec3};

use super::Contact;
use super::pair::spring_key;
use crate::model::Model;

impl Contact {
    /// Adds to the candidates the pairs of the pending tets with the
    /// contactable set at positions `x`, searched with margin `b/2 + moved`
    /// (`moved` bounds every watched node's distance from its reference),
    /// merged in ascending order; the nodes of the pending tets not yet
    /// watched are watched from here. Not inlined, so that a profile names
    /// it.
    #[inline(never)]
    pub(super) fn add_candidates(&mut self, model: &Model, x: &[Vec3], moved: Real) {
        let margin = 0.5 * self.settings.buffer + moved;
        self.spheres(model, x);
        let pending: Vec<usize> =
            self.pending.iter().map(|t| self.list.binary_search(t).expect("a pending tet is contactable")).collect();
        // A box around the pending tets' spheres: a partner's centre lies
        // within its own radius plus `2 margin` of it.
        let (mut lo, mut hi) = ([Real::INFINITY; 3], [Real::NEG_INFINITY; 3]);
        for &i in &pending {
            for k in 0..3 {
                lo[k] = lo[k].min(self.centers[i][k] - self.radii[i]);
                hi[k] = hi[k].max(self.centers[i][k] + self.radii[i]);
            }
        }
        let near: Vec<usize> = (0..self.list.len())
            .filter(|&j| {
                let (c, reach) = (&self.centers[j], self.radii[j] + 2.0 * margin);
                (0..3).all(|k| c[k] >= lo[k] - reach && c[k] <= hi[k] + reach)
            })
            .collect();
        // The sphere pairs, each once (a pair of two pending tets from the
        // smaller's side), as `a · 2³² + b` to sort.
        let mut found: Vec<u64> = Vec::new();
        for &i in &pending {
            let (ci, ri) = (&self.centers[i], self.radii[i]);
            for &j in &near {
                let cj = &self.centers[j];
                let reach = ri + self.radii[j] + 2.0 * margin;
                let d2 = (ci.x - cj.x).powi(2) + (ci.y - cj.y).powi(2) + (ci.z - cj.z).powi(2);
                if d2 <= reach * reach && j != i && (j > i || pending.binary_search(&j).is_err()) {
                    let (a, b) = spring_key(self.list[i], self.list[j]);
                    found.push(u64::from(a) << 32 | u64::from(b));
                }
            }
        }
        found.sort_unstable();
        // Kept: the pairs not yet candidates that may touch and that no face
        // plane separates by `2 margin`.
        let gap = 2.0 * margin;
        let at = |t: u32| model.tets[t as usize].map(|n| x[n as usize]);
        let mut known = 0;
        let mut added: Vec<(u32, u32)> = Vec::new();
        for key in found {
            let pair = ((key >> 32) as u32, key as u32);
            known += self.candidates[known..].partition_point(|c| *c < pair);
            if self.candidates.get(known) == Some(&pair) {
                continue;
            }
            let (a, b) = pair;
            if self.may_touch(model, a, b) && !separated_by_face_plane(&at(a), &at(b), gap) {
                added.push(pair);
            }
        }
        self.candidates = merge_unique(&self.candidates, &added);
        self.certificates.cache(&self.candidates);

        let mut fresh: Vec<u32> = self
            .pending
            .iter()
            .flat_map(|&t| model.tets[t as usize])
            .filter(|n| self.nodes.binary_search(n).is_err())
            .collect();
        fresh.sort_unstable();
        fresh.dedup();
        self.watch(&fresh, x);
        self.pending.clear();
        self.additions += 1;
    }

    /// Adds `fresh` (ascending, none watched yet) to the watched nodes,
    /// with their positions in `x` as references.
    fn watch(&mut self, fresh: &[u32], x: &[Vec3]) {
        if fresh.is_empty() {
            return;
        }
        let nodes = std::mem::take(&mut self.nodes);
        let x_ref = std::mem::take(&mut self.x_ref);
        self.nodes.reserve(nodes.len() + fresh.len());
        self.x_ref.reserve(nodes.len() + fresh.len());
        let mut j = 0;
        for (&n, r) in nodes.iter().zip(&x_ref) {
            while j < fresh.len() && fresh[j] < n {
                self.nodes.push(fresh[j]);
                self.x_ref.push(x[fresh[j] as usize]);
                j += 1;
            }
            self.nodes.push(n);
            self.x_ref.push(*r);
        }
        for &n in &fresh[j..] {
            self.nodes.push(n);
            self.x_ref.push(x[n as usize]);
        }
    }
}

/// The ascending union of two ascending lists, each element once.
fn merge_unique<T: Ord + Copy>(a: &[T], b: &[T]) -> Vec<T> {
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        match a[i].cmp(&b[j]) {
            std::cmp::Ordering::Less => {
                out.push(a[i]);
                i += 1;
            }
            std::cmp::Ordering::Greater => {
                out.push(b[j]);
                j += 1;
            }
            std::cmp::Ordering::Equal => {
                out.push(a[i]);
                i += 1;
                j += 1;
            }
        }
    }
    out.extend_from_slice(&a[i..]);
    out.extend_from_slice(&b[j..]);
    out
}

#[cfg(test)]
mod tests {
    use super::merge_unique;

    #[test]
    fn the_union_is_ascending_with_each_pair_once() {
        let a = [(0, 1), (0, 5), (2, 3), (7, 9)];
        let b = [(0, 2), (0, 5), (7, 8), (8, 9), (9, 10)];
        let expected = [(0, 1), (0, 2), (0, 5), (2, 3), (7, 8), (7, 9), (8, 9), (9, 10)];
        assert_eq!(merge_unique(&a, &b), expected);
        assert_eq!(merge_unique(&b, &a), expected);
        assert_eq!(merge_unique(&a, &[]), a);
        assert_eq!(merge_unique(&[], &b), b);
    }
}
