//! The contact pass's side of the gradient model's energy-consistent kicks
//! (`onset.rs` holds their arithmetic): which candidate pairs are corrected
//! and what each leaves for the next pass, the pairs that have separated
//! and left the candidates with a debt still to pay, and the order in which
//! all of them are summed into nodal forces.

use femdem_core::{Real, Vec3};

use super::pair::{PairForce, PairMap, spring_key};
use super::{Contact, onset};
use crate::model::Model;

/// `force` (candidate pair `tets`' result at this pass) with the
/// energy-consistent correction of its normal force (`onset.rs`) and what
/// it leaves for the next pass, where its force is the gradient of its
/// energy or it is out of contact with a debt left (a pair in contact
/// whose force is not the gradient is only marked as followed); `held`
/// what the last pass left, `x` the pair's nodes' positions, `v` the
/// velocities that moved them over the step `dt`, `primed` whether a pass
/// ran before.
#[allow(clippy::too_many_arguments)]
pub(super) fn corrected(
    force: Option<PairForce>,
    tets: [u32; 2],
    held: &PairMap<onset::Held>,
    x: &[[Vec3; 4]; 2],
    nodes: &[[u32; 4]; 2],
    v: &[Vec3],
    dt: Real,
    primed: bool,
) -> Option<PairForce> {
    let before = held.get(&spring_key(tets[0], tets[1]));
    let now = match &force {
        None => None,
        Some(f) if f.exact => Some((&f.normal, f.energy)),
        // Not the gradient of its energy: followed, not corrected (its
        // debt, if it had one, dropped), so that it starts afresh once it
        // is.
        Some(f) => return Some(PairForce { onset: Some(onset::Held::untracked()), ..*f }),
    };
    if before.is_none() && now.is_none() {
        return None;
    }
    let dx = nodes.map(|t| t.map(|n| v[n as usize] * dt));
    let (kick, next) = onset::step(before, now, x, &dx, primed)?;
    Some(match force {
        Some(f) => PairForce { kick, onset: Some(next), ..f },
        None => PairForce { onset: Some(next), ..PairForce::kick_only(tets, kick) },
    })
}

/// The candidates' results (ascending pairs) and the orphans' (ascending,
/// none a candidate: `Contact::orphans`) merged in ascending pair order, so
/// that a pair's forces are summed at the same place whether detection
/// still lists it or not (the sums' bits do not depend on the buffer or on
/// when detection ran).
pub(super) fn by_pair<'a>(
    results: impl Iterator<Item = &'a PairForce>,
    orphans: &'a [PairForce],
) -> impl Iterator<Item = &'a PairForce> {
    let key = |r: &PairForce| spring_key(r.tets[0], r.tets[1]);
    let (mut results, mut orphans) = (results.peekable(), orphans.iter().peekable());
    std::iter::from_fn(move || match (results.peek(), orphans.peek()) {
        (Some(&r), Some(&o)) if key(o) < key(r) => orphans.next(),
        (Some(_), _) => results.next(),
        (None, _) => orphans.next(),
    })
}

impl Contact {
    /// The corrections (`onset.rs`) of the pairs the last pass left a debt
    /// to that are no longer candidates (detection drops pairs that have
    /// separated), in ascending pair order: out of contact, they carry
    /// only their corrections until the debt is paid.
    pub(super) fn orphans(&self, model: &Model, x: &[Vec3], v: &[Vec3], dt: Real) -> Vec<PairForce> {
        let mut keys: Vec<(u32, u32)> =
            self.held.keys().copied().filter(|k| self.candidates.binary_search(k).is_err()).collect();
        keys.sort_unstable();
        keys.into_iter()
            .filter_map(|(a, b)| {
                let nodes = [model.tets[a as usize], model.tets[b as usize]];
                let xs = nodes.map(|t| t.map(|n| x[n as usize]));
                corrected(None, [a, b], &self.held, &xs, &nodes, v, dt, self.primed)
            })
            .collect()
    }

    /// With [`ContactModel::Gradient`]: the pairs the last pass followed
    /// for the energy-consistent kicks (`onset.rs`): those in contact, and
    /// those that have separated with a debt still to pay.
    pub fn kicked_pairs(&self) -> usize {
        self.held.len()
    }
}
