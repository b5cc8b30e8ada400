//! The contact pass's part of a solver snapshot (`crate::snapshot`):
//! what `Contact::encode` writes and `Contact::decoded` reads back,
//! every index checked against the model.

use femdem_core::Vec3;

use super::{Contact, ContactEnergy};
use crate::SolverError;
use crate::model::Model;
use crate::snapshot::{Decoder, Encoder, expect_count, snapshot_error};

impl Contact {
    /// Writes the pass's evolving state to a solver snapshot (see
    /// `crate::snapshot`): the contactable set, cracked vertices and their
    /// pieces, bonded pairs, the candidates with the watched nodes and their
    /// reference positions, staleness and the pending tets, the last pass's
    /// touched nodes with their forces and velocities, the energy account
    /// and counters, the friction springs, the Eq. 18 ramp counters and the pairs that
    /// started overlapped with their offsets (maps sorted by key), what
    /// cracks newly allowed to touch since the last pass, and the negligible
    /// pairs' certificates (`certify.rs`). Scratch
    /// buffers (NBS, spheres, pair results, the started pairs' forces) are not
    /// written.
    pub(crate) fn encode(&self, e: &mut Encoder) {
        e.bools(&self.contactable);
        e.u32s(self.stars.pieces());
        e.bools(&self.cracked);
        e.u32s(&self.list);
        let mut bonded: Vec<(u32, u32)> = self.bonded.iter().copied().collect();
        bonded.sort_unstable();
        put_pairs(e, &bonded);
        put_pairs(e, &self.candidates);
        e.u32s(&self.nodes);
        e.vec3s(&self.x_ref);
        e.bool(self.stale);
        e.u32s(&self.pending);
        e.u32s(&self.touched);
        for &n in &self.touched {
            e.vec3(&self.force[n as usize]);
            e.vec3(&self.friction_force[n as usize]);
        }
        e.vec3s(&self.v_before);
        let en = &self.energy;
        [
            en.contact,
            en.friction,
            en.friction_absorbed,
            en.spring_booked,
            en.normal_ahead,
            en.friction_ahead,
            en.released,
            en.released_ahead,
            en.held,
        ]
        .into_iter()
        .for_each(|x| e.f64(x));
        e.count(self.active_pairs);
        e.u64(self.detections);
        e.u64(self.additions);
        e.f64(self.spring_energy);
        e.f64(self.potential);
        let mut stick: Vec<_> = self.stick.iter().map(|(&k, &s)| (k, s)).collect();
        stick.sort_unstable_by_key(|&(k, _)| k);
        e.count(stick.len());
        for ((a, b), s) in stick {
            e.u32(a);
            e.u32(b);
            e.vec3(&s);
        }
        let mut ramp: Vec<_> = self.ramp.iter().map(|(&k, &n)| (k, n)).collect();
        ramp.sort_unstable();
        e.count(ramp.len());
        for ((a, b), n) in ramp {
            e.u32(a);
            e.u32(b);
            e.u32(n);
        }
        let mut started: Vec<_> = self.started.iter().map(|(&k, &off)| (k, off)).collect();
        started.sort_unstable_by_key(|&(k, _)| k);
        e.count(started.len());
        for ((a, b), off) in started {
            e.u32(a);
            e.u32(b);
            e.f64(off);
        }
        // What cracks newly allowed since the last pass (empty between the
        // steps of a run; not after `Solver::break_joints` or before the
        // first step).
        e.bool(self.newly.first);
        e.u32s(&self.newly.tets);
        put_pairs(e, &self.newly.pairs);
        put_pairs(e, &self.newly.couples);
        // The certificates (sorted by pair), the anchored nodes with their
        // anchors, the tets still to anchor, the epoch's age and count.
        let cert = &self.certificates;
        let mut map: Vec<_> = cert.map.iter().map(|(&k, &r)| (k, r)).collect();
        map.sort_unstable_by_key(|&(k, _)| k);
        e.count(map.len());
        for ((a, b), r) in map {
            e.u32(a);
            e.u32(b);
            e.f64(r);
        }
        let anchored: Vec<u32> = (0..cert.anchored.len() as u32).filter(|&n| cert.anchored[n as usize]).collect();
        e.bool(!cert.anchored.is_empty());
        e.u32s(&anchored);
        anchored.iter().for_each(|&n| e.vec3(&cert.anchor[n as usize]));
        e.u32s(&cert.to_anchor);
        e.u32(cert.age);
        e.u64(cert.bounded);
    }

    /// This pass (its settings and the model's fixed tables) with the
    /// evolving state read from a snapshot written by [`Contact::encode`];
    /// sizes and indices are checked against `model`.
    pub(crate) fn decoded(&self, model: &Model, d: &mut Decoder<'_>) -> Result<Contact, SolverError> {
        let (n_tets, n_nodes) = (model.tets.len(), model.num_nodes());
        let tet = |t: u32| -> Result<u32, SolverError> {
            if (t as usize) < n_tets { Ok(t) } else { Err(snapshot_error(format!("contact: tet {t} of {n_tets}"))) }
        };
        let node = |n: u32| -> Result<u32, SolverError> {
            if (n as usize) < n_nodes { Ok(n) } else { Err(snapshot_error(format!("contact: node {n} of {n_nodes}"))) }
        };
        let mut c = self.clone();
        c.contactable = d.bools()?;
        expect_count("contactable tets", c.contactable.len(), n_tets)?;
        let pieces = d.u32s()?;
        expect_count("star entries", pieces.len(), self.stars.pieces().len())?;
        c.stars.set_pieces(pieces);
        c.cracked = d.bools()?;
        expect_count("original vertices", c.cracked.len(), self.cracked.len())?;
        c.list = d.u32s()?.into_iter().map(tet).collect::<Result<_, _>>()?;
        c.bonded = get_pairs(d, &tet)?.into_iter().collect();
        c.candidates = get_pairs(d, &tet)?;
        c.nodes = d.u32s()?.into_iter().map(node).collect::<Result<_, _>>()?;
        c.x_ref = d.vec3s()?;
        expect_count("detection positions", c.x_ref.len(), c.nodes.len())?;
        c.stale = d.bool()?;
        c.pending = d.u32s()?.into_iter().map(tet).collect::<Result<_, _>>()?;
        if let Some(t) = c.pending.iter().find(|t| c.list.binary_search(t).is_err()) {
            return Err(snapshot_error(format!("contact: pending tet {t} is not contactable")));
        }
        c.force.iter_mut().chain(c.friction_force.iter_mut()).chain(c.total.iter_mut()).for_each(|f| {
            *f = Vec3::zeros();
        });
        c.is_touched.fill(false);
        c.touched = d.u32s()?.into_iter().map(node).collect::<Result<_, _>>()?;
        for &n in &c.touched {
            let n = n as usize;
            c.force[n] = d.vec3()?;
            c.friction_force[n] = d.vec3()?;
            c.total[n] = c.force[n] + c.friction_force[n];
            c.is_touched[n] = true;
        }
        c.v_before = d.vec3s()?;
        expect_count("velocities of touched nodes", c.v_before.len(), c.touched.len())?;
        c.energy = ContactEnergy {
            contact: d.f64()?,
            friction: d.f64()?,
            friction_absorbed: d.f64()?,
            spring_booked: d.f64()?,
            normal_ahead: d.f64()?,
            friction_ahead: d.f64()?,
            released: d.f64()?,
            released_ahead: d.f64()?,
            held: d.f64()?,
        };
        c.active_pairs = d.count()?;
        c.detections = d.u64()?;
        c.additions = d.u64()?;
        c.spring_energy = d.f64()?;
        c.potential = d.f64()?;
        c.stick.clear();
        for _ in 0..d.count()? {
            let key = (tet(d.u32()?)?, tet(d.u32()?)?);
            c.stick.insert(key, d.vec3()?);
        }
        c.stick_next.clear();
        c.ramp.clear();
        for _ in 0..d.count()? {
            let key = (tet(d.u32()?)?, tet(d.u32()?)?);
            c.ramp.insert(key, d.u32()?);
        }
        c.started.clear();
        c.started_next.clear();
        for _ in 0..d.count()? {
            let key = (tet(d.u32()?)?, tet(d.u32()?)?);
            c.started.insert(key, d.f64()?);
        }
        c.in_contact.clear();
        c.newly.clear();
        c.newly.first = d.bool()?;
        for t in d.u32s()? {
            c.record_contactable(tet(t)?);
        }
        c.newly.pairs = get_pairs(d, &tet)?;
        c.newly.couples = get_pairs(d, &tet)?;
        let cert = &mut c.certificates;
        cert.map.clear();
        for _ in 0..d.count()? {
            let key = (tet(d.u32()?)?, tet(d.u32()?)?);
            cert.map.insert(key, d.f64()?);
        }
        let any = d.bool()?;
        cert.anchor.clear();
        cert.anchored.clear();
        if any {
            cert.anchor.resize(n_nodes, Vec3::zeros());
            cert.anchored.resize(n_nodes, false);
        }
        for n in d.u32s()? {
            let n = node(n)? as usize;
            if !any {
                return Err(snapshot_error("contact: anchors before the first epoch"));
            }
            cert.anchored[n] = true;
            cert.anchor[n] = d.vec3()?;
        }
        cert.to_anchor = d.u32s()?.into_iter().map(tet).collect::<Result<_, _>>()?;
        cert.age = d.u32()?;
        cert.bounded = d.u64()?;
        cert.cache(&c.candidates);
        cert.count_certified();
        // Written by every pass before its booking reads it.
        c.started_force.fill(Vec3::zeros());
        Ok(c)
    }
}

/// A length-prefixed list of tet pairs.
fn put_pairs(e: &mut Encoder, pairs: &[(u32, u32)]) {
    e.count(pairs.len());
    for &(a, b) in pairs {
        e.u32(a);
        e.u32(b);
    }
}

/// Reads what [`put_pairs`] wrote, each index checked by `tet`.
fn get_pairs(
    d: &mut Decoder<'_>,
    tet: &impl Fn(u32) -> Result<u32, SolverError>,
) -> Result<Vec<(u32, u32)>, SolverError> {
    let n = d.count()?;
    (0..n).map(|_| Ok((tet(d.u32()?)?, tet(d.u32()?)?))).collect()
}
