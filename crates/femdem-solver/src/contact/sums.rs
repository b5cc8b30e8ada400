//! The contact pass's sums: each pair's result (and each separated pair's
//! kick, `debts.rs`) in ascending pair order into the nodal normal and
//! friction forces, the pairs in contact, the friction springs, the
//! offsets and ramps the next pass reads, and the velocities the account
//! books them with.

use femdem_core::Vec3;
use rayon::prelude::*;

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
    /// what the next pass reads (springs, offsets, ramps, the kicks' debts);
    /// and, when `certifying`, the certificates' updates of the pass
    /// (`Certificates::book`), beside the nodal sums.
    pub(super) fn sum_into_nodes(&mut self, model: &Model, orphans: &[PairForce], v: &[Vec3], certifying: bool) {
        // Taken out while the sums write the pass's other fields.
        let results = std::mem::take(&mut self.results);
        let pairs: Vec<&PairForce> = by_pair(results.iter().filter_map(|r| r.0.as_deref()), orphans).collect();
        let chunk = self.force.len().div_ceil(NODE_CHUNKS).max(1);
        let mut touched: Vec<Vec<u32>> = vec![Vec::new(); NODE_CHUNKS];
        let (force, friction_force) = (&mut self.force, &mut self.friction_force);
        let (started_force, is_touched) = (&mut self.started_force, &mut self.is_touched);
        // Each chunk of nodes sums every pair's shares on its own nodes, in
        // the pairs' order: each node's sum is the serial one, bit for bit,
        // whatever the chunks and threads.
        let sums = || {
            force
                .par_chunks_mut(chunk)
                .zip(friction_force.par_chunks_mut(chunk))
                .zip(started_force.par_chunks_mut(chunk))
                .zip(is_touched.par_chunks_mut(chunk))
                .zip(touched.par_iter_mut())
                .enumerate()
                .for_each(|(c, ((((force, friction), started), is_touched), touched))| {
                    let first = c * chunk;
                    let range = first..first + force.len();
                    for r in &pairs {
                        let [a, b] = r.tets;
                        for (side, (t, sign)) in [(a, -1.0), (b, 1.0)].into_iter().enumerate() {
                            for (k, &n) in model.tets[t as usize].iter().enumerate() {
                                let n = n as usize;
                                if !range.contains(&n) {
                                    continue;
                                }
                                let i = n - first;
                                if !is_touched[i] {
                                    is_touched[i] = true;
                                    touched.push(n as u32);
                                }
                                force[i] += r.normal[side][k] + r.kick[side][k];
                                friction[i] += r.friction * (r.weights[side][k] * sign);
                                if r.started.is_some() {
                                    started[i] += r.normal[side][k];
                                }
                            }
                        }
                    }
                    touched.sort_unstable();
                });
        };
        let ramp_fresh = self.settings.activation == Activation::Ramp && self.settings.ramp_steps > 0;
        // What the sums book per pair besides the nodal forces, in the
        // pairs' order, beside them.
        let books = || {
            self.active_pairs = 0;
            self.spring_energy = 0.0;
            self.potential = 0.0;
            self.in_contact.clear();
            for r in &pairs {
                let [a, b] = r.tets;
                if let Some(held) = r.onset {
                    self.held_next.insert(spring_key(a, b), held);
                }
                if r.touching {
                    self.active_pairs += 1;
                    self.in_contact.push((a, b));
                }
                if r.friction != Vec3::zeros() || r.spring_energy > 0.0 {
                    let key = spring_key(a, b);
                    debug_assert!(self.stick_next.last().is_none_or(|s| s.0 < key), "pairs out of order");
                    self.stick_next.push((key, r.spring));
                    self.spring_energy += r.spring_energy;
                }
                self.potential += r.energy;
                if let Some(off) = r.started {
                    self.started_next.insert(spring_key(a, b), off);
                }
                if r.fresh && ramp_fresh {
                    self.ramp.entry(spring_key(a, b)).or_insert(0);
                }
            }
            if certifying {
                self.certificates.book(&self.candidates, results.iter().map(|r| r.1));
            }
        };
        rayon::join(sums, books);
        drop(pairs);
        self.results = results;
        // The chunks' lists, each ascending, in the chunks' order.
        self.touched.clear();
        for t in &touched {
            self.touched.extend_from_slice(t);
        }
        self.v_before.clear();
        for &n in &self.touched {
            let n = n as usize;
            self.total[n] = self.force[n] + self.friction_force[n];
            self.v_before.push(v[n]);
        }
    }
}

/// The nodes are split into this many chunks, summed in parallel (each
/// over every pair, in the pairs' order); a fixed number, so that no
/// result depends on the threads.
const NODE_CHUNKS: usize = 4;
