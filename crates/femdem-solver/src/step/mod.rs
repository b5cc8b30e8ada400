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
//! # The energy account and its time-centring
//!
//! Every term of [`Energies`] belongs to `t_n`, the time of the record.
//! The state terms are evaluated at `t_n`: elastic energies from the tets'
//! and joints' stored-energy functions at `x_n`, the joints' dissipation
//! from their histories, and the kinetic energy as the leapfrog's own
//!
//! ```text
//! K_n = ½ Σ m v_{n−½} · v_{n+½}      (= ½ Σ m |v_n|² − ⅛ Σ m |v_{n+½} − v_{n−½}|²)
//! ```
//!
//! Work is booked by intervals `[t_{n−1}, t_n]` with the trapezoidal rule
//! on the path the nodes took, `½ (f_{n−1} + f_n) · (x_n − x_{n−1})`, for
//! the surface loads and gravity, the drives' reactions and the contact
//! and friction forces (`Contact::book_work`). Step `n` knows `f_n`,
//! `v_{n−½}` and `v_{n+½}`: it books `½ Δt f_n · v_{n−½}`, which closes the
//! interval before `t_n`, and holds over `½ Δt f_n · v_{n+½}`, which opens
//! the one after and is booked by step `n + 1`. With `f = m (v_{n+½} −
//! v_{n−½}) / Δt` the total force on a node (driven nodes included: their
//! reaction is what makes it so), the identity
//!
//! ```text
//! K_n − K_{n−1} = ½ Δt (f_{n−1} + f_n) · v_{n−½}
//! ```
//!
//! holds exactly, so kinetic energy and booked work agree to round-off,
//! prescribed velocities and their jumps included (a platen set moving
//! from rest books `½ m V²` of work as it gains `½ m V²` of kinetic
//! energy); for a linear elastic body the trapezoidal work of its forces
//! is also exactly its change of strain energy, so the account of a
//! linear run balances to round-off at any stable step. The viscous
//! forces' trapezoid is booked as dissipation, `Δt ∫ η D(v_{n−½}) : D(v̄)
//! dv` with `v̄ = ½ (v_{n−3/2} + v_{n−½})` (`crate::forces::Dissipation`),
//! and a joint books its work with the same rule on its own opening and
//! slip (`femdem_fracture::JointHistory::work`). What is left is the
//! truncation of the nonlinear laws (neo-Hookean tets; the joints'
//! rotating frame and changing area), and the viscous operator taken on
//! `x_n` for the whole interval. The account's constant is `B_0`, the
//! balance of step 0: the initial kinetic and elastic energy
//! `½ Σ m |v_{−½}|² + U_0` up to terms of that first step's forces. The
//! watch on it is in `crate::ledger`.
//!
//! Measured on the bundled cases with the energies evaluated at every
//! step, the largest `|B_n − B_0|` over the run's energy scale
//! (`crate::ledger`): elastic bar 4·10⁻⁷ (was 0.53 when the work was
//! booked through `t_{n+½}` against the kinetic energy of `v_n`), pulled
//! bar 1.8·10⁻⁴ (0.018), Brazilian split 5·10⁻⁵ (4.6·10⁻³), with joints
//! in a band 1.2·10⁻⁴ (5.2·10⁻³) (`docs/reliability.md`).

mod external;
mod failures;
mod intervene;
mod prescribed;
mod record;
mod resident;
mod start;
mod update;

use femdem_core::{Real, Vec3};
use femdem_fracture::JointHistory;

pub use prescribed::held_nodes;
pub use record::{FailureCounts, StepRecord};

use std::time::Instant;

use crate::SolverError;
use crate::clock::{StageTimes, lap};
use crate::contact::{Contact, ContactEnergy, ContactModel, ContactSettings};
use crate::device::OnDevice;
use crate::forces::{Dissipation, ForceSums, Want, Workspace, internal_forces};
use crate::ledger::{Ledger, energy_floor};
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

/// What a run is about, fixed once the solver is built: the model, the
/// loads and the step parameters (the time step changes only by
/// [`Solver::set_params`]), and what is derived from them alone.
pub(crate) struct Scene {
    /// The model ([`Solver::model`]).
    pub(crate) model: Model,
    /// The loads ([`Solver::loads`]).
    pub(crate) loads: Loads,
    /// The step parameters.
    pub(crate) params: StepParams,
    /// Whether any material is viscous.
    pub(crate) viscous: bool,
    /// The energy scale's floor ([`crate::ledger`]), J.
    pub(crate) floor: f64,
}

/// What changes step by step: everything a checkpoint holds
/// ([`Solver::snapshot`]) to continue bit for bit.
pub(crate) struct Evolving {
    /// Positions, velocities, joint histories, step and time
    /// ([`Solver::state`]).
    pub(crate) state: State,
    /// Every work and energy term, with the half steps held over and the
    /// watch on the balance (`crate::ledger`).
    pub(crate) ledger: Ledger,
    /// Every joint failure so far.
    pub(crate) failures: Vec<Failure>,
    /// Contact: its pairs, springs, ramps, detection and certificates.
    pub(crate) contact: Option<Contact>,
    /// With viscous materials, the velocities of the step before,
    /// `v_{n−3/2}` at step `n` (the dissipation's trapezoid,
    /// [`Dissipation`]); empty otherwise.
    pub(crate) v_before: Vec<Vec3>,
    /// The record of the last step.
    pub(crate) record: StepRecord,
}

/// Buffers and caches a step fills and then reads: they are not
/// checkpointed, and a GPU pipeline would sit beside them.
pub(crate) struct Pipeline {
    /// The force workspace ([`Solver::workspace`]).
    pub(crate) workspace: Workspace,
    /// External forces, prescribed components and drive targets.
    external: External,
    /// The update's per-chunk sums.
    update: Update,
    /// Whether `workspace.internal` holds the internal forces of the last
    /// step of this state: false before the first step and after
    /// [`Solver::restore`] (the pipeline is not checkpointed).
    pub(crate) forces_current: bool,
    /// The step on a GPU ([`Solver::use_device`]), or `None` for the CPU.
    pub(crate) device: Option<OnDevice>,
    /// Host wall-clock time of the steps by stage (`clock.rs`; not a
    /// result).
    pub(crate) times: StageTimes,
}

/// An explicit solver: the scene it runs (model, loads, step
/// parameters), the state that evolves, and the pipeline of buffers a step
/// works in.
pub struct Solver {
    pub(crate) scene: Scene,
    pub(crate) evolving: Evolving,
    pub(crate) pipeline: Pipeline,
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
            drive_work: vec![0.0; loads.drives.len()],
            surface_forces: vec![Vec3::zeros(); loads.surfaces.len()],
            surface_work: vec![0.0; loads.surfaces.len()],
            ..StepRecord::default()
        };
        Ok(Solver {
            evolving: Evolving {
                v_before: if viscous { vec![Vec3::zeros(); n] } else { Vec::new() },
                ledger: Ledger::new(loads.surfaces.len(), loads.drives.len()),
                state,
                failures: Vec::new(),
                contact: None,
                record,
            },
            pipeline: Pipeline {
                workspace: Workspace::new(&model),
                update: Update::new(n),
                external,
                forces_current: false,
                device: None,
                times: StageTimes::default(),
            },
            scene: Scene { floor: energy_floor(&model), model, loads, params, viscous },
        })
    }

    /// The time step, s.
    pub fn dt(&self) -> Real {
        self.scene.params.dt
    }

    /// Changes the time step from the next step on.
    pub fn set_params(&mut self, params: StepParams) {
        self.scene.params = params;
    }

    /// The energy account after the last step.
    pub fn energies(&self) -> &Energies {
        &self.evolving.ledger.energies
    }

    /// Contact's terms of the energy account, when contact is enabled
    /// ([`Solver::enable_contact`]).
    pub fn contact_energy(&self) -> Option<&ContactEnergy> {
        self.evolving.contact.as_ref().map(|_| &self.evolving.ledger.contact)
    }

    /// The work the normal contact forces have absorbed up to `t_n`, with
    /// what the failed joints handed over counted as absorbed
    /// ([`Contact::normal_work`]), J; `None` without contact.
    pub fn contact_normal_work(&self) -> Option<Real> {
        self.evolving.contact.as_ref().map(|c| c.normal_work(&self.evolving.ledger.contact))
    }

    /// Every joint failure so far, in order.
    pub fn failures(&self) -> &[Failure] {
        &self.evolving.failures
    }

    /// The contact pass, when enabled ([`Solver::enable_contact`]).
    pub fn contact(&self) -> Option<&Contact> {
        self.evolving.contact.as_ref()
    }

    /// Chooses the normal contact force ([`ContactModel`]) before the first
    /// step (no state depends on it then), instead of the one
    /// [`ContactSettings::model`] gave.
    ///
    /// # Errors
    /// Without contact, or after the first step.
    pub fn set_contact_model(&mut self, model: ContactModel) -> Result<(), String> {
        if self.evolving.state.step != 0 {
            return Err(format!(
                "the run is at step {}: the contact model is chosen before the first",
                self.evolving.state.step
            ));
        }
        let contact = self.evolving.contact.as_mut().ok_or("the case has no contact")?;
        contact.settings.model = model;
        Ok(())
    }

    /// The record of the last step (all zero before the first).
    pub fn record(&self) -> &StepRecord {
        &self.evolving.record
    }

    /// Which nodes have all three velocity components prescribed from the
    /// first step on (as [`held_nodes`]).
    pub fn held_nodes(&self) -> Vec<bool> {
        self.pipeline.external.held_nodes(&self.scene.loads)
    }

    /// The model: mesh, materials, joints, masses. Read-only from outside
    /// the crate: a model is fixed once the solver is built.
    pub fn model(&self) -> &Model {
        &self.scene.model
    }

    /// The loads. Read-only from outside the crate (the external forces'
    /// caches are derived from them).
    pub fn loads(&self) -> &Loads {
        &self.scene.loads
    }

    /// The evolving state: positions, velocities, joint histories, step
    /// and time. Read-only from outside the crate: it changes by
    /// [`Solver::step`] and by the methods that book what they change in
    /// the energy account ([`Solver::damp`], [`Solver::kick`],
    /// [`Solver::set_velocity`], [`Solver::start_displaced`],
    /// [`Solver::restore`]).
    ///
    /// With the step on a device ([`Solver::use_device`]) the joint
    /// histories are the device's as of the last [`Solver::sync_device`].
    /// With a resident device so are the positions and velocities, except
    /// that a step that asked for stresses or energies brings back those
    /// after it (what a run's output and guard read), a step with failures
    /// those of its own `t_n` (for the failure record), and every step its
    /// drives' nodes' at its `t_n`.
    ///
    /// ```compile_fail
    /// fn tamper(s: &mut femdem_solver::Solver) {
    ///     s.state.v[0].x = 1.0; // private: use Solver::kick
    /// }
    /// ```
    pub fn state(&self) -> &State {
        &self.evolving.state
    }

    /// The force workspace: the tet stresses of the last step that asked
    /// for them (`Want::stress`), the internal forces. With the step on a
    /// device ([`Solver::use_device`]) the element slots are not filled,
    /// and the internal forces of a resident device are the drives' nodes'
    /// only until [`Solver::sync_device`].
    pub fn workspace(&self) -> &Workspace {
        &self.pipeline.workspace
    }

    /// Position of node `i` at the time of the last record, `t_n`:
    /// `x_{n+1} − Δt v_{n+½}` (the step has already moved the nodes on).
    pub fn recorded_position(&self, i: usize) -> Vec3 {
        self.evolving.state.x[i] - self.evolving.state.v[i] * self.scene.params.dt
    }

    /// Sets an initial velocity field (as `v_{−½}`, and as the `v_{−3/2}`
    /// the first step's viscous dissipation reads: a motion that was
    /// steady before the start). Called after the first step, it changes
    /// the state outside the step: the energy account sees the change of
    /// kinetic energy as energy no force accounts for, and
    /// [`Solver::check_energy`] stops a run on it.
    pub fn set_velocity(&mut self, v: impl Fn(&Vec3) -> Vec3) {
        self.edit_on_host();
        for (vi, x) in self.evolving.state.v.iter_mut().zip(&self.scene.model.x0) {
            *vi = v(x);
        }
        if self.scene.viscous {
            self.evolving.v_before.copy_from_slice(&self.evolving.state.v);
        }
    }

    /// Advances one step from `t_n` to `t_{n+1}` and returns the record of
    /// step `n`. With `want.energy`, the state terms of the energy account
    /// are evaluated at `t_n` (always at step 0, whose balance is the
    /// account's constant); with `want.stress`, the tet stresses of `t_n`
    /// are kept in [`Solver::workspace`].
    ///
    /// The step runs on a worker thread of rayon's current pool (inline
    /// when called from one): its parallel passes then start by work
    /// stealing among the pool's threads, instead of each being injected
    /// into the pool from outside it and waited for, two thread wake-ups
    /// per pass (`docs/performance.md`, "Contact at the speed of the bulk,
    /// first part", item 3). The
    /// results do not depend on it.
    pub fn step(&mut self, want: Want) -> &StepRecord {
        rayon::scope(|_| self.advance(want));
        &self.evolving.record
    }

    /// Host wall-clock time of the steps so far by stage, `None` before the
    /// first (`clock.rs`): where the time goes, on the CPU or a device.
    /// Varies from run to run; not a result.
    pub fn stage_times(&self) -> Option<StageTimes> {
        Some(self.pipeline.times).filter(|t| t.steps > 0)
    }

    /// Which compilation of the CPU's tet and joint passes and of the
    /// contact pair kernel the following steps run ([`VectorPath::Widest`](crate::VectorPath::Widest) by
    /// default). Both give the same results bit for bit; the choice exists
    /// to compare them (tests, `step_profile`).
    pub fn set_vector_path(&mut self, path: crate::VectorPath) {
        self.pipeline.workspace.path = path;
    }

    /// [`Solver::step`]'s work.
    fn advance(&mut self, want: Want) {
        let dt = self.scene.params.dt;
        let t = self.evolving.state.time;
        let want = Want { energy: want.energy || self.evolving.state.step == 0, ..want };
        if let Some(device) = &mut self.pipeline.device {
            let pushed = device.push_if_edited(&self.evolving.state, &self.evolving.v_before);
            if device.resident {
                if pushed {
                    // A decree or a restore may have made tets contactable.
                    self.watch_contactable().expect("the watched nodes fit where all nodes do");
                }
                self.advance_resident(want);
                return;
            }
        }
        let mut clock = Instant::now();
        let mut times = StageTimes { steps: 1, ..StageTimes::default() };
        // 1. Internal forces at x_n.
        let dissipation =
            if self.scene.viscous { Dissipation::Since(&self.evolving.v_before) } else { Dissipation::None };
        let sums = match &mut self.pipeline.device {
            Some(device) => device.internal_forces(
                &self.evolving.state.x,
                &self.evolving.state.v,
                &mut self.pipeline.workspace,
                want,
                dissipation,
            ),
            None => internal_forces(
                &self.scene.model,
                &self.evolving.state.x,
                &self.evolving.state.v,
                &mut self.evolving.state.joints,
                &mut self.pipeline.workspace,
                want,
                dissipation,
            ),
        };
        self.pipeline.forces_current = true;
        lap(&mut clock, &mut times.forces);
        // 2. Failures, handed to contact (which reads their histories).
        let first_new = self.evolving.failures.len();
        if let (Some(device), Some(_), true) = (&self.pipeline.device, &self.evolving.contact, sums.newly_failed > 0) {
            device.pull_failed_histories(&mut self.evolving.state.joints);
        }
        if sums.newly_failed > 0 {
            self.record_failures(t);
        }
        lap(&mut clock, &mut times.failures);
        // 3. Contact.
        if let Some(contact) = &mut self.evolving.contact {
            let before = contact.clock;
            contact.path = self.pipeline.workspace.path;
            contact.pass(&self.scene.model, &self.evolving.state.x, &self.evolving.state.v, dt);
            times.add_pass(&before, &contact.clock);
        }
        clock = Instant::now();
        let contact_forces = self.evolving.contact.as_ref().map(Contact::total_force);
        // 4. External forces and reactions.
        self.pipeline.external.evaluate(
            &self.scene.model,
            &self.scene.loads,
            &self.evolving.state,
            &self.pipeline.workspace.internal,
            contact_forces,
            dt,
            &mut self.evolving.record,
        );
        lap(&mut clock, &mut times.drives);
        // 5. The update.
        let powers = self.pipeline.update.advance(
            &self.scene.model,
            &self.scene.loads,
            &self.pipeline.external,
            &self.pipeline.workspace.internal,
            contact_forces,
            &mut self.evolving.state,
            &mut self.evolving.v_before,
            dt,
            want.energy,
        );
        self.pipeline.external.close_powers(&self.evolving.state.v);
        lap(&mut clock, &mut times.update);
        self.account(sums, powers, first_new, t, want);
        lap(&mut clock, &mut times.account);
        self.pipeline.times += times;
    }

    /// Stage 6 of the step: the energy account (centred on `t_n`: module
    /// documentation) and the record of step `n`; then the clock moves on.
    fn account(&mut self, sums: ForceSums, powers: update::Powers, first_new: usize, t: Real, want: Want) {
        let dt = self.scene.params.dt;
        let ledger = &mut self.evolving.ledger;
        ledger.gravity.book(0.5 * dt * powers.back, 0.5 * dt * powers.ahead);
        for (term, &(back, ahead)) in ledger.surfaces.iter_mut().zip(&self.pipeline.external.powers) {
            term.book(0.5 * dt * back, 0.5 * dt * ahead);
        }
        for (term, &(back, ahead)) in ledger.drives.iter_mut().zip(&self.pipeline.external.drive_halves) {
            term.book(back, ahead);
        }
        ledger.close();
        if let Some(contact) = &self.evolving.contact {
            contact.book_work(&mut ledger.contact, &self.evolving.state.v, dt);
            ledger.energies.contact = ledger.contact.contact + ledger.contact.handed();
            ledger.energies.friction = ledger.contact.friction;
        }
        let e = &mut ledger.energies;
        e.damping += dt * sums.dissipation_rate;
        if want.energy {
            e.kinetic = powers.kinetic;
            e.tet_elastic = sums.tet_energy;
            e.joint_elastic = sums.joint_energy;
            // What the failed joints handed over to contact is not fracture
            // energy (`ContactEnergy::handed`): moved to the contact term.
            e.fracture = sums.fracture - ledger.contact.handed();
            ledger.observe(self.evolving.state.step, t, self.scene.floor);
        }
        let r = &mut self.evolving.record;
        r.step = self.evolving.state.step;
        r.time = t;
        r.new_failures = first_new..self.evolving.failures.len();
        for f in &self.evolving.failures[first_new..] {
            r.failures.add(f.mode);
        }
        r.energies = ledger.energies;
        for (w, term) in r.surface_work.iter_mut().zip(&ledger.surfaces) {
            *w = term.total;
        }
        for (w, term) in r.drive_work.iter_mut().zip(&ledger.drives) {
            *w = term.total;
        }
        r.energies_current = want.energy;
        r.contact_pairs = self.evolving.contact.as_ref().map_or(0, |c| c.active_pairs);
        self.evolving.state.time += dt;
        self.evolving.state.step += 1;
    }

    /// Turns on contact (§2.3): `initial` are tet pairs in contact from the
    /// start (pre-existing fractures).
    ///
    /// Joints that have already failed (naturally or by
    /// [`Solver::break_joints`]) unbond their tets as if failing now,
    /// without the Eq. 18 ramp.
    ///
    /// # Panics
    /// With the bulk on a device already ([`Solver::use_device`]): turn
    /// contact on first.
    pub fn enable_contact(&mut self, settings: ContactSettings, initial: &[(u32, u32)]) {
        assert!(self.pipeline.device.is_none(), "Solver::enable_contact before Solver::use_device");
        self.evolving.contact = Some(Contact::new(&self.scene.model, settings, initial));
        // A new pass starts a new account (what an earlier one held over is
        // not this pass's).
        self.evolving.ledger.contact = ContactEnergy::default();
        for j in 0..self.evolving.state.joints.len() {
            if self.evolving.state.joints[j].failed {
                let xp = self.scene.model.joints[j].map(|n| self.evolving.state.x[n as usize]);
                let area = femdem_fracture::joint_kinematics(&xp).map_or(0.0, |k| k.frame.area);
                self.unbond(j, false, area);
            }
        }
    }
}
