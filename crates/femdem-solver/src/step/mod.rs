//! The explicit step of Eq. 19–20 as named stages, and the energy account.
//!
//! Scheme: the paper names forward Euler; femdem uses its symplectic form,
//! the central-difference (leapfrog) update
//!
//! ```text
//! a_n       = (f_int(x_n, v_{n−½}) + f_joint(x_n) + f_contact(x_n) + f_load(t_n)) / m   (Eq. 19–20)
//! v_{n+½}   = v_{n−½} + Δt a_n
//! x_{n+1}   = x_n + Δt v_{n+½}
//! ```
//!
//! which is second-order accurate, conserves energy to O(Δt²) without drift
//! for conservative forces, and is stable up to `Δt = 2/ω_max`; plain
//! forward Euler (`x_{n+1} = x_n + Δt v_n`) is unconditionally unstable for
//! an undamped oscillator. Prescribed velocity components are imposed on
//! `v_{n+½}` at time `t_n + Δt/2`, and the force the constraint had to
//! apply, `m (v_{n+½} − v_{n−½}) / Δt − f`, is the recorded reaction.
//!
//! One step, [`Solver::step`], runs these stages in order, each owning its
//! state:
//!
//! 1. **internal forces** (`crate::forces`): tets (Eq. 1–2) and joints
//!    (Eq. 3–13) at `x_n`, into the force workspace;
//! 2. **failures** (`failures.rs`): the joints that failed in stage 1 are
//!    recorded and handed to contact (one path, [`Solver::break_joints`]
//!    and [`Solver::enable_contact`] use it too);
//! 3. **contact** (`crate::contact`): detection and Eq. 17–18 forces with
//!    friction, into the contact pass's own buffer;
//! 4. **external forces** (`external.rs`): surface loads at `t_n` on the
//!    current geometry, gravity, and the drives' reactions;
//! 5. **update** (`update.rs`): `v_{n+½}`, `x_{n+1}`, prescribed
//!    components imposed;
//! 6. **energy** (here): the account below, then the [`StepRecord`].
//!
//! Energy account (exact for the leapfrog update: the change of the
//! half-step kinetic energy equals `Δt Σ f_n · v_n` with
//! `v_n = (v_{n−½} + v_{n+½}) / 2`): external work and reaction work are
//! accumulated as `Δt Σ f · v_n` each step, viscous dissipation as
//! `Δt ∫ η D:D dv`, the contact terms by the contact pass itself
//! ([`Contact::book_work`]); kinetic energy is reported with `v_n`, elastic
//! energy from the tets' and joints' stored-energy functions.

mod external;
mod failures;
mod prescribed;
mod record;
mod start;
mod update;

use femdem_core::{Real, Vec3};
use femdem_fracture::JointHistory;

pub use prescribed::held_nodes;
pub use record::{FailureCounts, StepRecord};

use crate::SolverError;
use crate::contact::{Contact, ContactSettings};
use crate::forces::{Want, Workspace, internal_forces};
use crate::loads::Loads;
use crate::model::Model;
use crate::state::{Energies, Failure, State};
use external::External;
use update::Update;

/// The parameters of a run, validated when made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepParams {
    dt: Real,
}

impl StepParams {
    /// A run with time step `dt`, s (see [`crate::stable_time_step`] for the
    /// largest stable one).
    ///
    /// # Errors
    /// [`SolverError::TimeStep`] unless `dt` is finite and > 0.
    pub fn new(dt: Real) -> Result<StepParams, SolverError> {
        if dt.is_finite() && dt > 0.0 { Ok(StepParams { dt }) } else { Err(SolverError::TimeStep(dt)) }
    }

    /// The time step, s.
    pub fn dt(&self) -> Real {
        self.dt
    }
}

/// An explicit solver: a model, its loads, its state.
pub struct Solver {
    /// The model.
    pub model: Model,
    /// The loads.
    pub loads: Loads,
    /// The state.
    pub state: State,
    params: StepParams,
    energies: Energies,
    /// The force workspace (holds the stresses of the last step that asked
    /// for them).
    pub workspace: Workspace,
    failures: Vec<Failure>,
    contact: Option<Contact>,
    external: External,
    update: Update,
    viscous: bool,
    record: StepRecord,
}

impl Solver {
    /// A solver at rest in the reference configuration.
    ///
    /// # Errors
    /// The inconsistencies [`held_nodes`] reports: a component prescribed
    /// twice, a rigid node not driven in all three components, a node
    /// without mass left free.
    pub fn new(model: Model, loads: Loads, params: StepParams) -> Result<Solver, SolverError> {
        let external = External::new(&model, &loads)?;
        let viscous = model.materials.iter().any(|(_, m)| m.viscosity() > 0.0);
        let n = model.num_nodes();
        let state = State {
            x: model.x0.clone(),
            v: vec![Vec3::zeros(); n],
            time: 0.0,
            step: 0,
            joints: vec![JointHistory::default(); model.joints.len()],
        };
        let record = StepRecord {
            drive_forces: vec![Vec3::zeros(); loads.drives.len()],
            drive_displacements: vec![Vec3::zeros(); loads.drives.len()],
            surface_forces: vec![Vec3::zeros(); loads.surfaces.len()],
            ..StepRecord::default()
        };
        Ok(Solver {
            workspace: Workspace::new(&model),
            update: Update::new(n),
            model,
            loads,
            state,
            params,
            energies: Energies::default(),
            failures: Vec::new(),
            contact: None,
            external,
            viscous,
            record,
        })
    }

    /// The time step, s.
    pub fn dt(&self) -> Real {
        self.params.dt
    }

    /// Changes the time step from the next step on.
    pub fn set_params(&mut self, params: StepParams) {
        self.params = params;
    }

    /// The energy account after the last step.
    pub fn energies(&self) -> &Energies {
        &self.energies
    }

    /// Every joint failure so far, in order.
    pub fn failures(&self) -> &[Failure] {
        &self.failures
    }

    /// The contact pass, when enabled ([`Solver::enable_contact`]).
    pub fn contact(&self) -> Option<&Contact> {
        self.contact.as_ref()
    }

    /// The record of the last step (all zero before the first).
    pub fn record(&self) -> &StepRecord {
        &self.record
    }

    /// Which nodes have all three velocity components prescribed.
    pub fn held_nodes(&self) -> Vec<bool> {
        self.external.held_nodes()
    }

    /// Position of node `i` at the time of the last record, `t_n`:
    /// `x_{n+1} − Δt v_{n+½}` (the step has already moved the nodes on).
    pub fn recorded_position(&self, i: usize) -> Vec3 {
        self.state.x[i] - self.state.v[i] * self.params.dt
    }

    /// Sets an initial velocity field (as `v_{−½}`).
    pub fn set_velocity(&mut self, v: impl Fn(&Vec3) -> Vec3) {
        for (vi, x) in self.state.v.iter_mut().zip(&self.model.x0) {
            *vi = v(x);
        }
    }

    /// Advances one step from `t_n` to `t_{n+1}` and returns the record of
    /// step `n`. With `want.energy`, the state terms of the energy account
    /// are evaluated at `t_n`; with `want.stress`, the tet stresses of `t_n`
    /// are kept in [`Solver::workspace`].
    pub fn step(&mut self, want: Want) -> &StepRecord {
        let dt = self.params.dt;
        let t = self.state.time;
        // 1. Internal forces at x_n.
        let sums = internal_forces(
            &self.model,
            &self.state.x,
            &self.state.v,
            &mut self.state.joints,
            &mut self.workspace,
            want,
            self.viscous,
        );
        // 2. Failures, handed to contact.
        let first_new = self.failures.len();
        if sums.newly_failed > 0 {
            self.record_failures(t);
        }
        // 3. Contact.
        if let Some(contact) = &mut self.contact {
            contact.pass(&self.model, &self.state.x, &self.state.v, dt);
        }
        let contact_forces = self.contact.as_ref().map(Contact::total_force);
        // 4. External forces and reactions.
        let reaction_work = self.external.evaluate(
            &self.model,
            &self.loads,
            &self.state,
            &self.workspace.internal,
            contact_forces,
            dt,
            &mut self.record,
        );
        // 5. The update.
        let (power, kinetic) = self.update.advance(
            &self.model,
            &self.loads,
            &self.external,
            &self.workspace.internal,
            contact_forces,
            &mut self.state,
            dt,
            want.energy,
        );
        // 6. The energy account and the record.
        let e = &mut self.energies;
        e.external_work += dt * power + reaction_work;
        if let Some(contact) = &mut self.contact {
            contact.book_work(&self.state.v, dt);
            e.contact = contact.energy.contact;
            e.friction = contact.energy.friction;
        }
        e.damping += dt * sums.dissipation_rate;
        if want.energy {
            e.kinetic = kinetic;
            e.tet_elastic = sums.tet_energy;
            e.joint_elastic = sums.joint_energy;
            e.fracture = sums.fracture;
        }
        let r = &mut self.record;
        r.step = self.state.step;
        r.time = t;
        r.new_failures = first_new..self.failures.len();
        for f in &self.failures[first_new..] {
            r.failures.add(f.mode);
        }
        r.energies = self.energies;
        r.energies_current = want.energy;
        r.contact_pairs = self.contact.as_ref().map_or(0, |c| c.active_pairs);
        self.state.time += dt;
        self.state.step += 1;
        &self.record
    }

    /// Replaces the evolving state that [`Solver::restore`] decoded (the
    /// node state is set by the caller).
    pub(crate) fn put_back(
        &mut self,
        energies: Energies,
        failures: Vec<Failure>,
        record: StepRecord,
        contact: Option<Contact>,
    ) {
        self.energies = energies;
        self.failures = failures;
        self.record = record;
        self.contact = contact;
    }

    /// Turns on contact (§2.3): `initial` are tet pairs in contact from the
    /// start (pre-existing fractures).
    ///
    /// Joints that have already failed (naturally or by
    /// [`Solver::break_joints`]) unbond their tets as if failing now,
    /// without the Eq. 18 ramp.
    pub fn enable_contact(&mut self, settings: ContactSettings, initial: &[(u32, u32)]) {
        self.contact = Some(Contact::new(&self.model, settings, initial));
        for j in 0..self.state.joints.len() {
            if self.state.joints[j].failed {
                self.unbond(j, false);
            }
        }
    }
}
