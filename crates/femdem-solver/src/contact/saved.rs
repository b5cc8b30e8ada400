//! The contact pass's part of a solver snapshot (`crate::snapshot`): its
//! evolving state as a serde value ([`SavedContact`]), every index checked
//! against the model when it is put back.

use femdem_core::{Real, Vec3};
use serde::{Deserialize, Serialize};

use super::Contact;
use super::onset::Held;
use crate::SolverError;
use crate::model::Model;
use crate::snapshot::{expect_count, snapshot_error};

/// A tet pair, `(a, b)` with `a < b`.
type Key = (u32, u32);

/// The contact pass's evolving state: the contactable set, cracked
/// vertices and their pieces, bonded pairs, the candidates with the watched
/// nodes and their reference positions, staleness and the pending tets,
/// the last pass's touched nodes with their forces and velocities, the
/// counters, the friction springs, the Eq. 18 ramp counters, the pairs that
/// started overlapped with their offsets, what cracks newly allowed to
/// touch since the last pass, and the negligible pairs' certificates
/// (`certify.rs`), and what the gradient model's followed pairs leave for
/// its kicks (applied forces, energies, debts: `onset.rs`). Maps are written sorted by key, so that a snapshot is a
/// function of the state alone. Not in it: the settings and the model's
/// fixed tables (the solver is built again from the same input), scratch
/// buffers every pass overwrites before reading (NBS, spheres, pair
/// results, the started pairs' forces), and what is derived from the
/// state (the certificates' cache and count, the touched flags); contact's
/// energy terms are in the ledger.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct SavedContact {
    contactable: Vec<bool>,
    pieces: Vec<u32>,
    cracked: Vec<bool>,
    list: Vec<u32>,
    bonded: Vec<Key>,
    candidates: Vec<Key>,
    nodes: Vec<u32>,
    x_ref: Vec<Vec3>,
    stale: bool,
    pending: Vec<u32>,
    /// Each touched node with its normal and friction force.
    touched: Vec<(u32, Vec3, Vec3)>,
    v_before: Vec<Vec3>,
    active_pairs: usize,
    detections: u64,
    additions: u64,
    spring_energy: Real,
    potential: Real,
    stick: Vec<(Key, Vec3)>,
    ramp: Vec<(Key, u32)>,
    started: Vec<(Key, Real)>,
    newly_first: bool,
    newly_tets: Vec<u32>,
    newly_pairs: Vec<Key>,
    newly_couples: Vec<Key>,
    certificates: Vec<(Key, Real)>,
    /// The anchored nodes with their anchors; `None` before the first
    /// epoch (no anchor table yet).
    anchors: Option<Vec<(u32, Vec3)>>,
    to_anchor: Vec<u32>,
    age: u32,
    bounded: u64,
    /// With `ContactModel::Gradient`: what the followed pairs (in contact,
    /// or separated with a debt) leave for the kicks (`onset.rs`), and
    /// whether a pass has run.
    held: Vec<(Key, Held)>,
    primed: bool,
}

/// A map's entries sorted by key.
fn sorted<V: Copy>(map: &std::collections::HashMap<Key, V, impl std::hash::BuildHasher>) -> Vec<(Key, V)> {
    let mut v: Vec<(Key, V)> = map.iter().map(|(&k, &x)| (k, x)).collect();
    v.sort_unstable_by_key(|&(k, _)| k);
    v
}

impl Contact {
    /// The pass's evolving state, for a snapshot.
    pub(crate) fn saved(&self) -> SavedContact {
        let mut bonded: Vec<Key> = self.bonded.iter().copied().collect();
        bonded.sort_unstable();
        let cert = &self.certificates;
        SavedContact {
            contactable: self.contactable.clone(),
            pieces: self.stars.pieces().to_vec(),
            cracked: self.cracked.clone(),
            list: self.list.clone(),
            bonded,
            candidates: self.candidates.clone(),
            nodes: self.nodes.clone(),
            x_ref: self.x_ref.clone(),
            stale: self.stale,
            pending: self.pending.clone(),
            touched: self
                .touched
                .iter()
                .map(|&n| (n, self.force[n as usize], self.friction_force[n as usize]))
                .collect(),
            v_before: self.v_before.clone(),
            active_pairs: self.active_pairs,
            detections: self.detections,
            additions: self.additions,
            spring_energy: self.spring_energy,
            potential: self.potential,
            stick: self.stick.clone(),
            ramp: sorted(&self.ramp),
            started: sorted(&self.started),
            // Empty between the steps of a run; not after
            // `Solver::break_joints` or before the first step.
            newly_first: self.newly.first,
            newly_tets: self.newly.tets.clone(),
            newly_pairs: self.newly.pairs.clone(),
            newly_couples: self.newly.couples.clone(),
            certificates: sorted(&cert.map),
            anchors: (!cert.anchored.is_empty()).then(|| {
                (0..cert.anchored.len() as u32)
                    .filter(|&n| cert.anchored[n as usize])
                    .map(|n| (n, cert.anchor[n as usize]))
                    .collect()
            }),
            to_anchor: cert.to_anchor.clone(),
            age: cert.age,
            bounded: cert.bounded,
            held: sorted(&self.held),
            primed: self.primed,
        }
    }

    /// This pass (its settings and the model's fixed tables) with the
    /// evolving state `s`; sizes and indices are checked against `model`.
    pub(crate) fn restored(&self, model: &Model, s: SavedContact) -> Result<Contact, SolverError> {
        let (n_tets, n_nodes) = (model.tets.len(), model.num_nodes());
        let tet = |t: u32| -> Result<u32, SolverError> {
            if (t as usize) < n_tets { Ok(t) } else { Err(snapshot_error(format!("contact: tet {t} of {n_tets}"))) }
        };
        let node = |n: u32| -> Result<u32, SolverError> {
            if (n as usize) < n_nodes { Ok(n) } else { Err(snapshot_error(format!("contact: node {n} of {n_nodes}"))) }
        };
        let tets = |v: Vec<u32>| v.into_iter().map(tet).collect::<Result<Vec<u32>, _>>();
        let pairs =
            |v: Vec<Key>| v.into_iter().map(|(a, b)| Ok((tet(a)?, tet(b)?))).collect::<Result<Vec<Key>, SolverError>>();
        let mut c = self.clone();
        expect_count("contactable tets", s.contactable.len(), n_tets)?;
        c.contactable = s.contactable;
        expect_count("star entries", s.pieces.len(), self.stars.pieces().len())?;
        c.stars.set_pieces(s.pieces);
        expect_count("original vertices", s.cracked.len(), self.cracked.len())?;
        c.cracked = s.cracked;
        c.list = tets(s.list)?;
        c.bonded = pairs(s.bonded)?.into_iter().collect();
        c.candidates = pairs(s.candidates)?;
        c.nodes = s.nodes.into_iter().map(node).collect::<Result<_, _>>()?;
        expect_count("detection positions", s.x_ref.len(), c.nodes.len())?;
        c.x_ref = s.x_ref;
        c.stale = s.stale;
        c.pending = tets(s.pending)?;
        if let Some(t) = c.pending.iter().find(|t| c.list.binary_search(t).is_err()) {
            return Err(snapshot_error(format!("contact: pending tet {t} is not contactable")));
        }
        c.force.iter_mut().chain(c.friction_force.iter_mut()).chain(c.total.iter_mut()).for_each(|f| {
            *f = Vec3::zeros();
        });
        c.is_touched.fill(false);
        c.touched.clear();
        for (n, normal, friction) in s.touched {
            let i = node(n)? as usize;
            c.force[i] = normal;
            c.friction_force[i] = friction;
            c.total[i] = normal + friction;
            c.is_touched[i] = true;
            c.touched.push(n);
        }
        expect_count("velocities of touched nodes", s.v_before.len(), c.touched.len())?;
        c.v_before = s.v_before;
        c.active_pairs = s.active_pairs;
        c.detections = s.detections;
        c.additions = s.additions;
        c.spring_energy = s.spring_energy;
        c.potential = s.potential;
        c.stick.clear();
        for ((a, b), x) in s.stick {
            c.stick.push(((tet(a)?, tet(b)?), x));
        }
        c.stick.sort_unstable_by_key(|s| s.0);
        c.stick_next.clear();
        c.ramp.clear();
        for ((a, b), n) in s.ramp {
            c.ramp.insert((tet(a)?, tet(b)?), n);
        }
        c.started.clear();
        c.started_next.clear();
        for ((a, b), off) in s.started {
            c.started.insert((tet(a)?, tet(b)?), off);
        }
        c.in_contact.clear();
        c.newly.clear();
        c.newly.first = s.newly_first;
        for t in s.newly_tets {
            c.record_contactable(tet(t)?);
        }
        c.newly.pairs = pairs(s.newly_pairs)?;
        c.newly.couples = pairs(s.newly_couples)?;
        let cert = &mut c.certificates;
        cert.map.clear();
        for ((a, b), r) in s.certificates {
            cert.map.insert((tet(a)?, tet(b)?), r);
        }
        cert.anchor.clear();
        cert.anchored.clear();
        if let Some(anchors) = s.anchors {
            cert.anchor.resize(n_nodes, Vec3::zeros());
            cert.anchored.resize(n_nodes, false);
            for (n, at) in anchors {
                let n = node(n)? as usize;
                cert.anchored[n] = true;
                cert.anchor[n] = at;
            }
        }
        cert.to_anchor = tets(s.to_anchor)?;
        cert.age = s.age;
        cert.bounded = s.bounded;
        cert.cache(&c.candidates);
        cert.count_certified();
        c.held.clear();
        c.held_next.clear();
        for ((a, b), h) in s.held {
            c.held.insert((tet(a)?, tet(b)?), h);
        }
        c.primed = s.primed;
        // Written by every pass before its booking reads it.
        c.started_force.fill(Vec3::zeros());
        Ok(c)
    }
}
