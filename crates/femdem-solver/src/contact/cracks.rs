//! Which tets may touch: a failed joint handed to contact (Eq. 14–16:
//! the couple unbonded, its vertices cracked, the tets around them made
//! contactable) and the rule that decides whether two contactable tets may
//! exert contact forces on each other (the module documentation of
//! `contact`).

use femdem_core::Real;

use super::pair::spring_key;
use super::{Activation, Contact, ContactEnergy};
use crate::model::Model;

impl Contact {
    /// Hands failed joint `joint` of `model` to contact (Eq. 14–16): its
    /// two tets are unbonded, its three original vertices become *cracked*
    /// (the pieces around them are found again), and every tet around them
    /// — the node groups G1–G6 of Eq. 15 — becomes contactable. A joint that failed in compression
    /// (`compressed`: its mean opening was negative) has the contact force
    /// between its two tets ramped in over [`ContactSettings::ramp_steps`]
    /// steps (Eq. 18), so that the joint force, which vanishes at failure,
    /// is not replaced by a sudden contact force (with
    /// [`Activation::Offset`] the offset does that instead).
    ///
    /// `held` is the compression energy the joint held when it failed
    /// (`JointHistory::compression_energy`), J: it bounds what the couple's
    /// overlap may give back ([`ContactEnergy::handed`]) unless the couple
    /// starts from an offset (then its overlap gives nothing back).
    ///
    /// `energy` is the ledger's contact account.
    pub fn joint_failed(
        &mut self,
        model: &Model,
        joint: usize,
        compressed: bool,
        held: Real,
        energy: &mut ContactEnergy,
    ) {
        let tets = model.joint_tets[joint];
        let key = spring_key(tets[0], tets[1]);
        let offset = match self.settings.activation {
            Activation::Offset => true,
            Activation::Couple | Activation::Settle => !compressed,
            Activation::Paper | Activation::Ramp => false,
        };
        if !offset {
            energy.held += held;
        }
        if compressed && self.settings.ramp_steps > 0 && self.settings.activation != Activation::Offset {
            self.ramp.insert(key, 0);
        }
        if compressed {
            self.newly.couples.push(key);
        }
        // N4 N5 N6 share the original vertices of N3 N2 N1.
        let vertices = [0, 1, 2].map(|k| model.origin[model.joints[joint][k] as usize]);
        self.crack(model, &vertices, &tets, Some(key));
    }

    /// Unbonds the pair `unbond` (a failed joint's), marks `vertices`
    /// cracked, makes `tets` and every tet around those vertices
    /// contactable, and finds the vertices' pieces again; those tets become
    /// pending: whether they may touch others changed only for pairs with
    /// one of them in (see `incremental.rs`). The pairs this newly allows
    /// are recorded for the next pass (`start.rs`).
    pub(super) fn crack(&mut self, model: &Model, vertices: &[u32], tets: &[u32], unbond: Option<(u32, u32)>) {
        let before = self.allowed_in_stars(model, vertices);
        if let Some(key) = unbond {
            self.bonded.remove(&key);
        }
        let mut added: Vec<u32> = Vec::new();
        let mut add = |t: u32, contactable: &mut Vec<bool>| {
            if !contactable[t as usize] {
                contactable[t as usize] = true;
                added.push(t);
            }
        };
        for &t in tets {
            add(t, &mut self.contactable);
        }
        for &v in vertices {
            self.cracked[v as usize] = true;
            for &t in self.stars.of(v) {
                add(t, &mut self.contactable);
            }
            self.stars.split(model, v, &self.bonded);
        }
        for &t in &added {
            self.record_contactable(t);
        }
        self.certificates.to_anchor.extend_from_slice(&added);
        self.record_newly_allowed(model, vertices, &before);
        if !added.is_empty() {
            added.sort_unstable();
            let old = std::mem::take(&mut self.list);
            let mut merged = Vec::with_capacity(old.len() + added.len());
            let (mut i, mut j) = (0, 0);
            while i < old.len() || j < added.len() {
                if j == added.len() || (i < old.len() && old[i] < added[j]) {
                    merged.push(old[i]);
                    i += 1;
                } else {
                    merged.push(added[j]);
                    j += 1;
                }
            }
            self.list = merged;
        }
        self.pending.extend_from_slice(tets);
        for &v in vertices {
            self.pending.extend_from_slice(self.stars.of(v));
        }
        self.pending.sort_unstable();
        self.pending.dedup();
    }

    /// Whether tets `a` and `b` may exert contact forces on each other (see
    /// the module documentation).
    pub(super) fn may_touch(&self, model: &Model, a: u32, b: u32) -> bool {
        if model.tet_material[a as usize].is_rigid() && model.tet_material[b as usize].is_rigid() {
            return false;
        }
        if self.bonded.contains(&spring_key(a, b)) {
            return false;
        }
        let (ta, tb) = (model.tets[a as usize], model.tets[b as usize]);
        if ta.iter().any(|n| tb.contains(n)) {
            return false;
        }
        let ob = tb.map(|n| model.origin[n as usize]);
        let mut shared = [0u32; 3];
        let mut n_shared = 0;
        for &n in &ta {
            let v = model.origin[n as usize];
            if ob.contains(&v) {
                shared[n_shared] = v;
                n_shared += 1;
            }
        }
        match n_shared {
            0 => true,
            // A common face with no active joint: failed, or a pre-existing
            // fracture (Eq. 14).
            3 => true,
            _ => shared[..n_shared]
                .iter()
                .any(|&v| self.cracked[v as usize] && self.stars.piece(v, a) != self.stars.piece(v, b)),
        }
    }
}
