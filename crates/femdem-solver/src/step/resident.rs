//! The step with positions and velocities resident on a device
//! ([`crate::Residency::Auto`]): the same six stages as [`Solver::step`]'s,
//! with stage 1, stage 4's surface loads, stage 5 and the sums on the
//! device, and contact (stage 3) on the CPU but for the candidate pairs'
//! Eq. 17 contacts (with the potential model), which the device computes
//! at the pass's request (`Contact::pass_with`, one more read-back).
//!
//! With contact, the positions and velocities of the contactable tets'
//! nodes (what the contact pass reads: detection, pairs, friction; the
//! *watched* nodes) come back with the drives' nodes before the pass; the
//! contact forces of the nodes the pass touched, now or at the pass
//! before, go down before the update, and those nodes' new positions and
//! velocities come back after it (the pass's account books the work
//! against `v_{n+½}`). The watched list grows when joints fail (a crack
//! makes tets contactable).
//!
//! Each step reads back one word (how many joints failed) with the drives'
//! nodes (position, velocity, internal and surface-load force, for stage
//! 4's reactions and displacements, computed by the CPU's code), the seven
//! sums and each surface load's total force and two powers; a
//! step with failures also the failed joints and the positions and
//! velocities of `t_n` (the record needs the failed joints' geometry), and
//! a step that asks for stresses or energies the positions and velocities
//! after the update (and the stresses), so that what the output and the
//! run guard read of [`Solver::state`] is current after it. Joint
//! histories, the velocities of the step before and the internal forces
//! come back only with [`Solver::sync_device`].

use std::time::Instant;

use femdem_core::Vec3;
use femdem_gpu::{Evaluate, MotionSetup, Sum, SurfaceKind, SurfaceLoad};

use super::Solver;
use super::external::weight;
use super::prescribed::Claim;
use super::update::Powers;
use crate::clock::{StageTimes, lap};
use crate::contact::Contact;
use crate::forces::{ForceSums, Want};
use crate::loads;

impl Solver {
    /// Readies the device's update: masses, weights, the prescribed
    /// components, the drives' nodes, the surface loads; sends the state
    /// up.
    pub(crate) fn make_resident(&mut self) -> Result<(), femdem_gpu::GpuError> {
        let model = &self.scene.model;
        let loads = &self.scene.loads;
        let weights: Vec<Vec3> = (0..model.num_nodes()).map(|i| weight(model, loads, i)).collect();
        let claims: Vec<[u32; 3]> = self
            .pipeline
            .external
            .prescribed
            .iter()
            .map(|c| {
                c.map(|claim| match claim {
                    Claim::Free => 0,
                    Claim::Fixed => 1,
                    Claim::Drive(d) => 2 + u32::from(d),
                })
            })
            .collect();
        let mut listed: Vec<u32> = loads.drives.iter().flat_map(|d| d.nodes.iter().copied()).collect();
        listed.sort_unstable();
        listed.dedup();
        let surfaces: Vec<SurfaceLoad<'_>> = loads
            .surfaces
            .iter()
            .map(|l| SurfaceLoad {
                faces: &l.faces,
                kind: match l.kind {
                    loads::SurfaceKind::Pressure(p) => SurfaceKind::Pressure(p),
                    loads::SurfaceKind::Traction(t) => SurfaceKind::Traction(t),
                },
            })
            .collect();
        let setup = MotionSetup {
            mass: &model.mass,
            weight: &weights,
            claims: &claims,
            drives: loads.drives.len(),
            listed: &listed,
            surfaces: &surfaces,
        };
        let e = &self.evolving;
        // Failures the last CPU or stage-1 step flagged are not this path's
        // to clear (it clears only what it flags).
        self.pipeline.workspace.failed_now.fill(None);
        let device = self.pipeline.device.as_mut().expect("a device");
        device.make_resident(setup, &e.state.x, &e.state.v, &e.v_before, e.contact.is_some())?;
        if e.contact.as_ref().is_some_and(Contact::geometry_elsewhere) {
            // Compiled now rather than in the first pass (about a second
            // on an H200): a refusal is kept, and the pass clips on the CPU.
            device.bulk.prepare_pair_kernel();
        }
        device.touched.clear();
        device.watched = Vec::new();
        self.watch_contactable()
    }

    /// Has the device send back every step the positions and velocities
    /// of the contactable tets' nodes (what the contact pass reads), if
    /// they changed.
    pub(super) fn watch_contactable(&mut self) -> Result<(), femdem_gpu::GpuError> {
        let Some(contact) = &self.evolving.contact else { return Ok(()) };
        let model = &self.scene.model;
        let mut watched: Vec<u32> = contact.contactable().iter().flat_map(|&t| model.tets[t as usize]).collect();
        watched.sort_unstable();
        watched.dedup();
        let device = self.pipeline.device.as_mut().expect("a resident device");
        if watched != device.watched {
            device.bulk.set_watched(&watched)?;
            device.watched = watched;
        }
        Ok(())
    }

    /// [`Solver::step`]'s work with the state on the device.
    pub(super) fn advance_resident(&mut self, want: Want) {
        let dt = self.scene.params.dt;
        let t = self.evolving.state.time;
        let viscous = self.scene.viscous;
        let mut clock = Instant::now();
        let mut times = StageTimes::default();
        let device = self.pipeline.device.as_mut().expect("a resident device");
        let ws = &mut self.pipeline.workspace;
        // 1. Internal forces at x_n, on the device, with the sums asked
        // for and the drives' nodes' state read back together.
        let mut sums_wanted = Vec::new();
        if viscous {
            sums_wanted.push(Sum::Dissipation);
        }
        if want.energy {
            sums_wanted.extend([Sum::TetEnergy, Sum::JointEnergy, Sum::Fracture]);
        }
        let evaluate = Evaluate { stress: want.stress, energy: want.energy, dissipation: viscous };
        let factors: Vec<_> = self.scene.loads.surfaces.iter().map(|l| l.ramp.factor(t)).collect();
        let mut back = std::mem::take(&mut device.back);
        device.bulk.forces_resident_into(evaluate, &sums_wanted, &factors, &mut back);
        device.synced = false;
        self.pipeline.forces_current = true;
        if want.stress {
            ws.stress.copy_from_slice(&device.bulk.stresses());
        }
        let newly_failed = device.take_failures(&mut ws.failed_now, back.failed > 0);
        let state = &mut self.evolving.state;
        let internal = &mut self.pipeline.workspace.internal;
        let f_surface = &mut self.pipeline.external.f_surface;
        for (&i, &[x, v, f, s]) in device.listed.iter().zip(&back.listed) {
            let i = i as usize;
            (state.x[i], state.v[i], internal[i], f_surface[i]) = (x, v, f, s);
        }
        for (&i, &[x, v]) in device.watched.iter().zip(&back.watched) {
            (state.x[i as usize], state.v[i as usize]) = (x, v);
        }
        device.back = back;
        lap(&mut clock, &mut times.forces);
        // 2. Failures: the record reads the failed joints' positions (and
        // contact, unbonding their tets, every node's).
        let first_new = self.evolving.failures.len();
        if newly_failed > 0 {
            device.pull_motion(&mut self.evolving.state);
            if self.evolving.contact.is_some() {
                device.pull_failed_histories(&mut self.evolving.state.joints);
            }
            self.record_failures(t);
            self.watch_contactable().expect("the watched nodes fit where all nodes do");
        }
        lap(&mut clock, &mut times.failures);
        // 3. Contact, on the CPU from the contactable tets' nodes.
        let mut contact_down = Vec::new();
        if let Some(contact) = &mut self.evolving.contact {
            // The pairs' Eq. 17 contacts on the device, at its x_n (the
            // watched nodes' positions the pass reads are those).
            let bulk = &mut self.pipeline.device.as_mut().expect("a resident device").bulk;
            let on_device = &mut times.geometry_device;
            let mut geometry = |pairs: &[[u32; 2]], omits: Option<&[f64]>, penalty: f64, found: &mut Vec<_>| {
                let start = Instant::now();
                let answered = bulk.pair_geometry_into(pairs, omits, penalty, found, bounded).is_ok();
                *on_device += start.elapsed();
                answered
            };
            let (x, v) = (&self.evolving.state.x, &self.evolving.state.v);
            let before = contact.clock;
            contact.path = self.pipeline.workspace.path;
            contact.pass_with(&self.scene.model, x, v, dt, Some(&mut geometry));
            times.add_pass(&before, &contact.clock);
            clock = Instant::now();
            let device = self.pipeline.device.as_mut().expect("a resident device");
            // The nodes touched now or at the pass before (zero now where
            // no longer touched), ascending.
            let mut nodes = std::mem::take(&mut device.touched);
            nodes.extend_from_slice(contact.touched());
            nodes.sort_unstable();
            nodes.dedup();
            let total = contact.total_force();
            contact_down = nodes.iter().map(|&n| (n, total[n as usize])).collect();
            device.touched = contact.touched().to_vec();
            // The contact forces to send down, with the pair loop.
            lap(&mut clock, &mut times.pairs);
        }
        clock = Instant::now();
        let contact_forces = self.evolving.contact.as_ref().map(Contact::total_force);
        // 4. External forces: the surface loads on the device (above), the
        // drives' reactions from their nodes' state by the CPU's code.
        self.pipeline.external.evaluate_drives(
            &self.scene.model,
            &self.scene.loads,
            &self.evolving.state,
            &self.pipeline.workspace.internal,
            contact_forces,
            dt,
            &mut self.evolving.record,
        );
        lap(&mut clock, &mut times.drives);
        // 5. The update, on the device; every sum comes back with it, and
        // with contact the new state of the nodes whose forces went down.
        let external = &self.pipeline.external;
        let drives: Vec<(Vec3, bool)> = external.targets.iter().copied().zip(external.active.iter().copied()).collect();
        let device = self.pipeline.device.as_mut().expect("a resident device");
        let totals = device.bulk.advance(dt, &drives, viscous, &contact_down);
        let state = &mut self.evolving.state;
        for (&(i, _), &[x, v]) in contact_down.iter().zip(&totals.contact_nodes) {
            (state.x[i as usize], state.v[i as usize]) = (x, v);
        }
        for (k, load) in totals.loads.iter().enumerate() {
            self.evolving.record.surface_forces[k] = load.force;
            self.pipeline.external.powers[k] = (load.back, load.ahead);
        }
        let total = |s: Sum| totals[s];
        let powers =
            Powers { back: total(Sum::WeightBack), ahead: total(Sum::WeightAhead), kinetic: total(Sum::Kinetic) };
        let mut sums = ForceSums { newly_failed, ..ForceSums::default() };
        if viscous {
            sums.dissipation_rate = total(Sum::Dissipation);
        }
        if want.energy {
            sums.tet_energy = total(Sum::TetEnergy);
            sums.joint_energy = total(Sum::JointEnergy);
            sums.fracture = total(Sum::Fracture);
        }
        // The state the output and the guard read after this step.
        if want.stress || want.energy {
            device.pull_motion(&mut self.evolving.state);
        }
        lap(&mut clock, &mut times.update);
        // 6. The account and the record, as on the CPU.
        self.account(sums, powers, first_new, t, want);
        lap(&mut clock, &mut times.account);
        times.steps = 1;
        self.pipeline.times += times;
    }
}

/// The device's pair result as `femdem_contact`'s.
fn bounded(p: femdem_gpu::pairs::PairBounded) -> femdem_contact::Bounded {
    use femdem_gpu::pairs::PairBounded;
    match p {
        PairBounded::Negligible(bound) => femdem_contact::Bounded::Negligible(bound),
        PairBounded::Contact(c) => femdem_contact::Bounded::Contact(femdem_contact::TetTetContact {
            on_a: c.on_a,
            on_b: c.on_b,
            centre: c.centre,
        }),
    }
}
