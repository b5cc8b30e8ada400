//! The explicit update of Eq. 19–20 and the energy account.
//!
//! Scheme: the paper names forward Euler; femdem uses its symplectic form,
//! the central-difference (leapfrog) update
//!
//! ```text
//! a_n       = (f_int(x_n, v_{n−½}) + f_joint(x_n) + f_load(t_n)) / m        (Eq. 19–20)
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
//! Energy account (exact for the leapfrog update: the change of the
//! half-step kinetic energy equals `Δt Σ f_n · v_n` with
//! `v_n = (v_{n−½} + v_{n+½}) / 2`): external work and reaction work are
//! accumulated as `Δt Σ f · v_n` each step, viscous dissipation as
//! `Δt ∫ η D:D dv`; kinetic energy is reported with `v_n`, elastic energy
//! from the tets' and joints' stored-energy functions.

use femdem_core::{Real, Vec3};
use rayon::prelude::*;

use crate::SolverError;
use femdem_fracture::{FailureMode, JointHistory, joint_kinematics};

use crate::contact::{Contact, ContactSettings};
use crate::forces::{CHUNK, ForceSums, Want, Workspace, internal_forces};
use crate::loads::{Loads, surface_forces};
use crate::model::Model;

const FREE: u16 = u16::MAX;
const FIXED: u16 = u16::MAX - 1;

/// Node positions and half-step velocities.
#[derive(Clone, Debug, PartialEq)]
pub struct State {
    /// Positions `x_n`, m.
    pub x: Vec<Vec3>,
    /// Velocities `v_{n−½}`, m/s.
    pub v: Vec<Vec3>,
    /// Time `t_n`, s.
    pub time: Real,
    /// Step count `n`.
    pub step: u64,
    /// Damage history of every joint.
    pub joints: Vec<JointHistory>,
}

/// Energies, J, at the last step that asked for them.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Energies {
    /// Kinetic energy `Σ ½ m |v_n|²`.
    pub kinetic: Real,
    /// Elastic energy stored in the tets.
    pub tet_elastic: Real,
    /// Elastic energy stored in the joints.
    pub joint_elastic: Real,
    /// Energy dissipated by viscous damping since the start.
    pub damping: Real,
    /// Work of loads, gravity and prescribed motions since the start.
    pub external_work: Real,
    /// Energy dissipated by joint softening and failure since the start.
    pub fracture: Real,
    /// Work absorbed by the normal contact forces since the start (the
    /// penalty potential's energy plus whatever the Eq. 18 ramp does not
    /// give back), plus the elastic energy of the friction springs now.
    pub contact: Real,
    /// Energy dissipated by Coulomb friction since the start: the work
    /// absorbed by friction forces less the energy the sticking springs
    /// still hold.
    pub friction: Real,
}

impl Energies {
    /// `kinetic + elastic + dissipated − external work`: constant in an
    /// exact solution (equal to the initial kinetic + elastic energy).
    pub fn balance(&self) -> Real {
        self.kinetic
            + self.tet_elastic
            + self.joint_elastic
            + self.damping
            + self.fracture
            + self.contact
            + self.friction
            - self.external_work
    }
}

/// A joint failure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Failure {
    /// Joint index.
    pub joint: u32,
    /// Time of failure, s (the start of the step that broke it).
    pub time: Real,
    /// Centroid of the joint's mid-plane at failure, m.
    pub centroid: Vec3,
    /// Mid-plane area at failure, m².
    pub area: Real,
    /// How it failed.
    pub mode: FailureMode,
}

/// What one step reports.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StepReport {
    /// Joints that failed in this step (their records are appended to
    /// [`Solver::failures`]).
    pub newly_failed: usize,
    /// Reaction force of each velocity drive (in [`Loads::drives`] order), N.
    pub drive_forces: Vec<Vec3>,
    /// Total force of each surface load, N.
    pub surface_forces: Vec<Vec3>,
}

/// An explicit solver: a model, its loads, its state.
pub struct Solver {
    /// The model.
    pub model: Model,
    /// The loads.
    pub loads: Loads,
    /// The state.
    pub state: State,
    /// Time step, s.
    pub dt: Real,
    /// The energy account.
    pub energies: Energies,
    /// The last step's report.
    pub report: StepReport,
    /// The force workspace (holds the last stresses when asked for).
    pub workspace: Workspace,
    /// Every joint failure so far, in order.
    pub failures: Vec<Failure>,
    /// The contact pass, when enabled ([`Solver::enable_contact`]).
    pub contact: Option<Contact>,
    contact_v: Vec<Vec3>,
    /// Work absorbed by friction forces so far, J.
    friction_absorbed: Real,
    /// Friction spring energy booked in `energies.contact`, J.
    contact_spring: Real,
    prescribed: Vec<[u16; 3]>,
    surface_nodes: Vec<u32>,
    f_surface: Vec<Vec3>,
    partials: Vec<[Real; 2]>,
    viscous: bool,
}

impl Solver {
    /// A solver at rest in the reference configuration.
    ///
    /// # Errors
    /// [`SolverError::Setup`] when a node is both fixed and driven, or two
    /// drives claim the same component, or a rigid node is not driven in
    /// all three components, or `dt` is not positive.
    pub fn new(model: Model, loads: Loads, dt: Real) -> Result<Solver, SolverError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(SolverError::Setup(format!("time step must be > 0, got {dt}")));
        }
        let n = model.num_nodes();
        let mut prescribed = vec![[FREE; 3]; n];
        let mut claim = |node: u32, c: usize, tag: u16, what: &str| -> Result<(), SolverError> {
            let slot = &mut prescribed[node as usize][c];
            if *slot != FREE && *slot != tag {
                return Err(SolverError::Setup(format!(
                    "node {node} component {} is prescribed twice ({what})",
                    ["x", "y", "z"][c]
                )));
            }
            *slot = tag;
            Ok(())
        };
        for f in &loads.fixed {
            for &node in &f.nodes {
                for c in (0..3).filter(|&c| f.components[c]) {
                    claim(node, c, FIXED, "fixed")?;
                }
            }
        }
        for (d, drive) in loads.drives.iter().enumerate() {
            for &node in &drive.nodes {
                for c in (0..3).filter(|&c| drive.components[c]) {
                    claim(node, c, d as u16, &format!("drive `{}`", drive.name))?;
                }
            }
        }
        if let Some(i) = (0..n).find(|&i| model.rigid_node[i] && prescribed[i].contains(&FREE)) {
            return Err(SolverError::Setup(format!(
                "node {i} of a rigid region is not driven in all three components: give its platen a velocity"
            )));
        }
        if let Some(i) = (0..n).find(|&i| model.mass[i] <= 0.0 && prescribed[i].contains(&FREE)) {
            return Err(SolverError::Setup(format!("node {i} has no mass and is not prescribed")));
        }
        let mut surface_nodes: Vec<u32> =
            loads.surfaces.iter().flat_map(|s| s.faces.iter().flatten().copied()).collect();
        surface_nodes.sort_unstable();
        surface_nodes.dedup();
        let viscous = model.materials.iter().any(|(_, m)| m.viscosity() > 0.0);
        let state = State {
            x: model.x0.clone(),
            v: vec![Vec3::zeros(); n],
            time: 0.0,
            step: 0,
            joints: vec![JointHistory::default(); model.joints.len()],
        };
        Ok(Solver {
            workspace: Workspace::new(&model),
            f_surface: vec![Vec3::zeros(); n],
            partials: vec![[0.0; 2]; n.div_ceil(CHUNK)],
            report: StepReport {
                newly_failed: 0,
                drive_forces: vec![Vec3::zeros(); loads.drives.len()],
                surface_forces: vec![Vec3::zeros(); loads.surfaces.len()],
            },
            model,
            loads,
            state,
            dt,
            energies: Energies::default(),
            failures: Vec::new(),
            contact: None,
            contact_v: Vec::new(),
            friction_absorbed: 0.0,
            contact_spring: 0.0,
            prescribed,
            surface_nodes,
            viscous,
        })
    }

    /// Which nodes have any prescribed component or belong to a rigid body
    /// (for [`crate::stable_time_step`]).
    pub fn held_nodes(&self) -> Vec<bool> {
        self.prescribed.iter().map(|p| p.iter().all(|&c| c != FREE)).collect()
    }

    /// Sets an initial velocity field (as `v_{−½}`).
    pub fn set_velocity(&mut self, v: impl Fn(&Vec3) -> Vec3) {
        for (vi, x) in self.state.v.iter_mut().zip(&self.model.x0) {
            *vi = v(x);
        }
    }

    /// Advances one step. With `want.energy`, the energies of `t_n` are
    /// refreshed; with `want.stress`, the tet stresses of `t_n` are kept in
    /// [`Solver::workspace`].
    pub fn step(&mut self, mut want: Want) -> ForceSums {
        want.dissipation = self.viscous;
        let dt = self.dt;
        let t = self.state.time;
        let sums = internal_forces(
            &self.model,
            &self.state.x,
            &self.state.v,
            &mut self.state.joints,
            &mut self.workspace,
            want,
        );
        self.report.newly_failed = sums.newly_failed;
        if sums.newly_failed > 0 {
            self.record_failures(t);
        }
        // Contact forces join the internal ones (so reactions include them).
        if let Some(contact) = &mut self.contact {
            contact.pass(&self.model, &self.state.x, &self.state.v, self.dt);
            self.contact_v.clear();
            for &n in contact.touched() {
                self.workspace.internal[n as usize] += contact.force[n as usize] + contact.friction_force[n as usize];
                self.contact_v.push(self.state.v[n as usize]);
            }
        }

        // Surface loads at t_n on the current geometry, in a fixed order.
        for &n in &self.surface_nodes {
            self.f_surface[n as usize] = Vec3::zeros();
        }
        for (k, load) in self.loads.surfaces.iter().enumerate() {
            let mut total = Vec3::zeros();
            let f_surface = &mut self.f_surface;
            surface_forces(load, &self.state.x, load.ramp.factor(t), |n, f| {
                f_surface[n as usize] += f;
                total += f;
            });
            self.report.surface_forces[k] = total;
        }

        // Reactions of the drives and fixed components (sequential, small).
        let t_half = t + 0.5 * dt;
        let mut reaction_work = 0.0;
        for (d, drive) in self.loads.drives.iter().enumerate() {
            let target = drive.velocity * drive.ramp.factor(t_half);
            let mut total = Vec3::zeros();
            for &node in &drive.nodes {
                let i = node as usize;
                let f = self.workspace.internal[i] + self.f_surface[i] + self.loads.gravity * self.model.mass[i];
                for c in 0..3 {
                    if self.prescribed[i][c] == d as u16 {
                        let r = self.model.mass[i] * (target[c] - self.state.v[i][c]) / dt - f[c];
                        total[c] += r;
                        reaction_work += dt * r * 0.5 * (target[c] + self.state.v[i][c]);
                    }
                }
            }
            self.report.drive_forces[d] = total;
        }

        // The update, in parallel over nodes.
        let model = &self.model;
        let loads = &self.loads;
        let prescribed = &self.prescribed;
        let internal = &self.workspace.internal;
        let f_surface = &self.f_surface;
        let targets: Vec<Vec3> = loads.drives.iter().map(|d| d.velocity * d.ramp.factor(t_half)).collect();
        let want_kinetic = want.energy;
        self.state
            .x
            .par_chunks_mut(CHUNK)
            .zip(self.state.v.par_chunks_mut(CHUNK))
            .zip(self.partials.par_iter_mut())
            .enumerate()
            .for_each(|(c, ((xs, vs), partial))| {
                let mut power = 0.0;
                let mut kinetic = 0.0;
                for (k, (x, v)) in xs.iter_mut().zip(vs.iter_mut()).enumerate() {
                    let i = c * CHUNK + k;
                    let m = model.mass[i];
                    let f_ext = f_surface[i] + loads.gravity * m;
                    let old = *v;
                    let mut new = if m > 0.0 { old + (internal[i] + f_ext) * (dt / m) } else { old };
                    for comp in 0..3 {
                        match prescribed[i][comp] {
                            FREE => {}
                            FIXED => new[comp] = 0.0,
                            d => new[comp] = targets[d as usize][comp],
                        }
                    }
                    let v_n = (old + new) * 0.5;
                    power += f_ext.dot(&v_n);
                    if want_kinetic {
                        kinetic += 0.5 * m * v_n.norm_squared();
                    }
                    *v = new;
                    *x += new * dt;
                }
                *partial = [power, kinetic];
            });
        let (power, kinetic) = self.partials.iter().fold((0.0, 0.0), |(p, k), q| (p + q[0], k + q[1]));
        self.energies.external_work += dt * power + reaction_work;
        if let Some(contact) = &self.contact {
            // Work done by the contact forces over the step, with v_n.
            let (mut normal, mut friction) = (0.0, 0.0);
            for (k, &n) in contact.touched().iter().enumerate() {
                let v_n = (self.contact_v[k] + self.state.v[n as usize]) * 0.5;
                normal += dt * contact.force[n as usize].dot(&v_n);
                friction += dt * contact.friction_force[n as usize].dot(&v_n);
            }
            self.friction_absorbed -= friction;
            self.energies.contact += contact.spring_energy - self.contact_spring - normal;
            self.energies.friction = self.friction_absorbed - contact.spring_energy;
            self.contact_spring = contact.spring_energy;
        }
        self.energies.damping += dt * sums.dissipation_rate;
        if want.energy {
            self.energies.kinetic = kinetic;
            self.energies.tet_elastic = sums.tet_energy;
            self.energies.joint_elastic = sums.joint_energy;
            self.energies.fracture = sums.fracture;
        }
        self.state.time += dt;
        self.state.step += 1;
        sums
    }

    /// Turns on contact (§2.3): `initial` are tet pairs in contact from the
    /// start (pre-existing fractures).
    ///
    /// Joints that have already failed (naturally or by
    /// [`Solver::break_joints`]) unbond their tets as if failing now
    /// (without the Eq. 18 ramp).
    pub fn enable_contact(&mut self, settings: ContactSettings, initial: &[(u32, u32)]) {
        let mut contact = Contact::new(&self.model, settings, initial);
        for (j, history) in self.state.joints.iter().enumerate() {
            if history.failed {
                contact.joint_failed(self.model.joint_tets[j], false);
            }
        }
        self.contact = Some(contact);
    }

    /// Breaks joints by decree (a notch or a saw cut seeded in an intact
    /// mesh, or a test of the switch to contact): each joint of `joints`
    /// not yet failed stops carrying force from the next step, and, with
    /// contact on, its two tets become contactable, with the Eq. 18 ramp if
    /// the joint is closed (mean opening < 0) at the current positions, as
    /// for a natural failure. It is not a material failure: nothing is
    /// added to [`Solver::failures`]. As for a natural failure, all the work
    /// done on the joint (its stored energy included) counts as `fracture`
    /// energy from then on.
    pub fn break_joints(&mut self, joints: &[u32]) {
        for &j in joints {
            let j = j as usize;
            let history = &mut self.state.joints[j];
            if history.failed {
                continue;
            }
            history.failed = true;
            let xp = self.model.joints[j].map(|n| self.state.x[n as usize]);
            if let Some(contact) = &mut self.contact {
                let opening = joint_kinematics(&xp).map_or(0.0, |k| k.opening.iter().sum::<Real>());
                contact.joint_failed(self.model.joint_tets[j], opening < 0.0);
            }
        }
    }

    /// Appends the joints that failed in the last force evaluation to
    /// [`Solver::failures`], in joint order.
    fn record_failures(&mut self, time: Real) {
        for (j, &code) in self.workspace.failed_now.iter().enumerate() {
            if code == 0 {
                continue;
            }
            let mode = match code {
                1 => FailureMode::Tensile,
                2 => FailureMode::Shear,
                _ => FailureMode::Mixed,
            };
            let xp = self.model.joints[j].map(|n| self.state.x[n as usize]);
            let centroid = xp.iter().sum::<Vec3>() / 6.0;
            let area = joint_kinematics(&xp).map_or(0.0, |k| k.frame.area);
            self.failures.push(Failure { joint: j as u32, time, centroid, area, mode });
            if let Some(contact) = &mut self.contact {
                let opening = joint_kinematics(&xp).map_or(0.0, |k| k.opening.iter().sum::<Real>());
                contact.joint_failed(self.model.joint_tets[j], opening < 0.0);
            }
        }
    }
}
