//! The contact pass's sums: each pair's result (and each separated pair's
//! kick, `debts.rs`) in ascending pair order into the nodal normal and
//! friction forces, the pairs in contact, the friction springs, the
//! offsets and ramps the next pass reads, and the velocities the account
//! books them with.

use femdem_core::Vec3;

use super::debts::by_pair;
use super::pair::{PairForce, spring_key};
use super::{Activation, Contact};
use crate::model::Model;

impl Contact {
    /// Sums the candidates' results of this pass and the separated pairs'
    /// kicks (`orphans`) in ascending pair order (the bits depend neither
    /// on the thread count nor on the detection): nodal forces
    /// ([`Contact::force`], [`Contact::friction_force`], their total), the
    /// touched nodes and their velocities `v`, the pairs in contact, and
    /// what the next pass reads (springs, offsets, ramps, the kicks' debts).
    pub(super) fn sum_into_nodes(&mut self, model: &Model, orphans: &[PairForce], v: &[Vec3]) {
        self.active_pairs = 0;
        self.spring_energy = 0.0;
        self.potential = 0.0;
        self.in_contact.clear();
        // Taken out while the sums write the pass's other fields.
        let results = std::mem::take(&mut self.results);
        for r in by_pair(results.iter().filter_map(|r| r.0.as_deref()), orphans) {
            let [a, b] = r.tets;
            if let Some(held) = r.onset {
                self.held_next.insert(spring_key(a, b), held);
            }
            if r.touching {
                self.active_pairs += 1;
                self.in_contact.push((a, b));
            }
            if r.friction != Vec3::zeros() || r.spring_energy > 0.0 {
                self.stick_next.insert(spring_key(a, b), r.spring);
                self.spring_energy += r.spring_energy;
            }
            self.potential += r.energy;
            if let Some(off) = r.started {
                self.started_next.insert(spring_key(a, b), off);
            }
            if r.fresh && self.settings.activation == Activation::Ramp && self.settings.ramp_steps > 0 {
                self.ramp.entry(spring_key(a, b)).or_insert(0);
            }
            for (side, (t, sign)) in [(a, -1.0), (b, 1.0)].into_iter().enumerate() {
                for (k, &n) in model.tets[t as usize].iter().enumerate() {
                    let n = n as usize;
                    if !self.is_touched[n] {
                        self.is_touched[n] = true;
                        self.touched.push(n as u32);
                    }
                    self.force[n] += r.normal[side][k] + r.kick[side][k];
                    self.friction_force[n] += r.friction * (r.weights[side][k] * sign);
                    if r.started.is_some() {
                        self.started_force[n] += r.normal[side][k];
                    }
                }
            }
        }
        self.results = results;
        self.touched.sort_unstable();
        self.v_before.clear();
        for &n in &self.touched {
            let n = n as usize;
            self.total[n] = self.force[n] + self.friction_force[n];
            self.v_before.push(v[n]);
        }
    }
}
