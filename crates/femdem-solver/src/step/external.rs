//! Stage 4 of the step: the external forces at `t_n` — surface loads on
//! the current geometry (`crate::loads::surface_forces`), gravity — and
//! the reactions of the prescribed velocities.

use femdem_core::{Real, Vec3};

use super::StepRecord;
use super::prescribed::{Claim, Prescribed, held, prescribed};
use crate::SolverError;
use crate::loads::{Loads, surface_forces};
use crate::model::Model;
use crate::state::State;

/// The external-force stage's state.
pub(super) struct External {
    /// Which components are prescribed, and by what.
    pub prescribed: Prescribed,
    /// Nodes that carry a surface load, ascending.
    surface_nodes: Vec<u32>,
    /// Surface-load force per node at `t_n` (zero off `surface_nodes`), N.
    pub f_surface: Vec<Vec3>,
    /// Each surface load's own nodal forces at `t_n` (a node once per
    /// loaded face it lies on), N: for each load's work.
    load_forces: Vec<Vec<(u32, Vec3)>>,
    /// Each surface load's power against `v_{n−½}`, `Σ f_n · v_{n−½}`, W.
    load_back: Vec<Real>,
    /// Each surface load's powers at `t_n`, `(Σ f_n · v_{n−½}, Σ f_n ·
    /// v_{n+½})` in W, once the update has run ([`External::close_powers`],
    /// or the device's sums).
    pub powers: Vec<(Real, Real)>,
    /// Each drive's reaction work over the two halves of the step, J:
    /// `(½ Δt Σ r · v_{n−½}, ½ Δt Σ r · v_{n+½})` (set by
    /// [`External::evaluate`]).
    pub drive_halves: Vec<(Real, Real)>,
    /// Each drive's target velocity at `t_n + Δt/2`, m/s.
    pub targets: Vec<Vec3>,
    /// Whether each drive prescribes `v_{n+½}` in this step
    /// ([`crate::VelocityDrive::active`] at `t_n + Δt/2`); an inactive
    /// drive's components move freely.
    pub active: Vec<bool>,
}

/// Gravity's force on node `i`, N: `g` times the node's physical mass
/// (its lumped mass divided by the mass-scaling factor). Mass scaling slows
/// the dynamics to lengthen the stable step; the weight a body carries must
/// not grow with it.
#[inline]
pub(super) fn weight(model: &Model, loads: &Loads, i: usize) -> Vec3 {
    loads.gravity * (model.mass[i] / model.mass_scaling)
}

impl External {
    pub fn new(model: &Model, loads: &Loads) -> Result<External, SolverError> {
        let prescribed = prescribed(model, loads)?;
        let mut surface_nodes: Vec<u32> =
            loads.surfaces.iter().flat_map(|s| s.faces.iter().flatten().copied()).collect();
        surface_nodes.sort_unstable();
        surface_nodes.dedup();
        Ok(External {
            prescribed,
            surface_nodes,
            f_surface: vec![Vec3::zeros(); model.num_nodes()],
            load_forces: vec![Vec::new(); loads.surfaces.len()],
            load_back: vec![0.0; loads.surfaces.len()],
            powers: vec![(0.0, 0.0); loads.surfaces.len()],
            drive_halves: vec![(0.0, 0.0); loads.drives.len()],
            targets: vec![Vec3::zeros(); loads.drives.len()],
            active: vec![true; loads.drives.len()],
        })
    }

    /// Sets each surface load's powers at `t_n` ([`External::powers`])
    /// given the velocities `v_{n+½}` of the update (the first was taken by
    /// [`External::evaluate`]).
    pub fn close_powers(&mut self, v: &[Vec3]) {
        for ((p, own), &back) in self.powers.iter_mut().zip(&self.load_forces).zip(&self.load_back) {
            *p = (back, own.iter().map(|&(n, f)| f.dot(&v[n as usize])).sum());
        }
    }

    /// The velocity component `c` of node `i` is given in this step:
    /// 0 for a fixed component, the target `v_{n+½}` of a started drive;
    /// `None` when it moves freely (a drive not yet started leaves it
    /// free). What the update imposes and what an intervention may change
    /// (`intervene.rs`).
    #[inline]
    pub fn imposed(&self, i: usize, c: usize) -> Option<Real> {
        match self.prescribed[i][c] {
            Claim::Free => None,
            Claim::Fixed => Some(0.0),
            Claim::Drive(d) if self.active[d as usize] => Some(self.targets[d as usize][c]),
            Claim::Drive(_) => None,
        }
    }

    pub fn held_nodes(&self, loads: &Loads) -> Vec<bool> {
        held(&self.prescribed, &loads.drives)
    }

    /// Evaluates the surface loads at `t_n = state.time` and the drives'
    /// targets at `t_n + Δt/2`, and records the load totals, the drives'
    /// reactions (given the internal and contact forces of this step; zero
    /// for a drive not yet started) and their mean displacements, and keeps
    /// each drive's reaction work over the step's two halves
    /// ([`External::drive_halves`]).
    #[allow(clippy::too_many_arguments)]
    pub fn evaluate(
        &mut self,
        model: &Model,
        loads: &Loads,
        state: &State,
        internal: &[Vec3],
        contact: Option<&[Vec3]>,
        dt: Real,
        record: &mut StepRecord,
    ) {
        self.evaluate_surfaces(loads, state, record);
        self.evaluate_drives(model, loads, state, internal, contact, dt, record);
    }

    /// The surface loads at `t_n` on the current geometry, in a fixed
    /// order: each node's force, each load's total and its power against
    /// `v_{n−½}`.
    fn evaluate_surfaces(&mut self, loads: &Loads, state: &State, record: &mut StepRecord) {
        let t = state.time;
        for &n in &self.surface_nodes {
            self.f_surface[n as usize] = Vec3::zeros();
        }
        for (k, load) in loads.surfaces.iter().enumerate() {
            let mut total = Vec3::zeros();
            let mut back = 0.0;
            let (f_surface, own) = (&mut self.f_surface, &mut self.load_forces[k]);
            own.clear();
            surface_forces(load, &state.x, load.ramp.factor(t), |n, f| {
                f_surface[n as usize] += f;
                own.push((n, f));
                total += f;
                back += f.dot(&state.v[n as usize]);
            });
            record.surface_forces[k] = total;
            self.load_back[k] = back;
        }
    }

    /// The drives' targets at `t_n + Δt/2`, reactions and displacements,
    /// given the surface-load forces of `t_n` ([`External::f_surface`] on
    /// the drives' nodes) and the internal and contact forces.
    #[allow(clippy::too_many_arguments)]
    pub fn evaluate_drives(
        &mut self,
        model: &Model,
        loads: &Loads,
        state: &State,
        internal: &[Vec3],
        contact: Option<&[Vec3]>,
        dt: Real,
        record: &mut StepRecord,
    ) {
        // Reactions of the drives (sequential, small).
        let t_half = state.time + 0.5 * dt;
        for (d, drive) in loads.drives.iter().enumerate() {
            let target = drive.velocity * drive.ramp.factor(t_half);
            self.targets[d] = target;
            let active = drive.active(t_half);
            self.active[d] = active;
            let mut total = Vec3::zeros();
            let mut u = Vec3::zeros();
            let (mut back_d, mut ahead_d) = (0.0, 0.0);
            for &node in &drive.nodes {
                let i = node as usize;
                u += state.x[i] - model.x0[i];
                if !active {
                    continue;
                }
                let f_in = match contact {
                    Some(c) => internal[i] + c[i],
                    None => internal[i],
                };
                let f = f_in + self.f_surface[i] + weight(model, loads, i);
                for c in 0..3 {
                    if self.prescribed[i][c] == Claim::Drive(d as u16) {
                        let r = model.mass[i] * (target[c] - state.v[i][c]) / dt - f[c];
                        total[c] += r;
                        back_d += 0.5 * dt * r * state.v[i][c];
                        ahead_d += 0.5 * dt * r * target[c];
                    }
                }
            }
            self.drive_halves[d] = (back_d, ahead_d);
            record.drive_forces[d] = total;
            record.drive_displacements[d] = u / drive.nodes.len().max(1) as Real;
        }
    }
}
