//! The step on a GPU ([`Solver::use_device`](crate::Solver::use_device),
//! [`Residency`]), run by `femdem-gpu`: here the device's copy of the model
//! and state ([`OnDevice`]), the stage-1-only path
//! ([`Residency::ForcesOnly`]), and the
//! bookkeeping of where the state is; the resident step is
//! `step/resident.rs`.
//!
//! Stage 1 only: each step uploads the positions and velocities (and, with
//! viscous materials, the velocities of the step before) and reads back
//! the gathered internal forces and which joints failed; the stresses, the
//! per-element energies and dissipation rates only on the steps that ask
//! for them, their sums taken on the host in the CPU pass's chunk order,
//! so equal element values give equal sums. Failures, external forces, the
//! update and the ledger stay on the CPU. The joint histories live on the
//! device in both paths: [`State::joints`] is brought up to date by
//! [`Solver::sync_device`](crate::Solver::sync_device).
//!
//! [`State::joints`]: crate::State::joints

use femdem_core::{Real, Vec3};
use femdem_fracture::{FailureMode, JointHistory};
use femdem_gpu::{Bulk, Evaluate, Gpu, GpuError, JointMesh, MotionSetup, TetMesh};

use crate::SolverError;
use crate::contact::Contact;
use crate::forces::{CHUNK, Dissipation, ForceSums, Want, Workspace};
use crate::model::Model;
use crate::state::State;

/// The device's copy of the model and its joint histories (and, resident,
/// of the positions and velocities).
pub(crate) struct OnDevice {
    pub(crate) bulk: Bulk,
    /// The adapter's name.
    pub(crate) adapter: String,
    /// Whether the host's joint histories (and, resident, positions,
    /// velocities, the velocities of the step before and the internal
    /// forces) are the device's.
    pub(crate) synced: bool,
    /// Whether the host changed its state since the device's last step
    /// (an intervention, a restore): sent up before the next step.
    pub(crate) edited: bool,
    /// Whether positions and velocities stay on the device between steps
    /// (the surface loads and the update run there), or go up and down
    /// every step.
    pub(crate) resident: bool,
    /// Resident: the nodes whose state stage 4 reads (the drives'),
    /// ascending, the order [`Bulk::forces_resident`] returns them in.
    pub(crate) listed: Vec<u32>,
    /// The joints whose `failed_now` entry the last step set.
    pub(crate) flagged: Vec<u32>,
    /// Resident with contact: the nodes whose contact force the device
    /// holds (those the host's last contact pass touched), ascending.
    pub(crate) touched: Vec<u32>,
    /// Resident with contact: the nodes whose positions and velocities
    /// come back every step (the contactable tets'), ascending.
    pub(crate) watched: Vec<u32>,
    /// What the last resident stage 1 read back, its vectors reused from
    /// step to step (the watched nodes of the paper's multi-layer mesh are
    /// 116 MB a step).
    pub(crate) back: femdem_gpu::Resident,
}

/// Bytes one step of stage 1 alone moves between host and device at
/// least: positions and velocities up, internal forces down (24 bytes a
/// node each), the velocities of the step before up with viscous
/// materials, and the count of failed joints down.
pub(crate) fn bytes_per_step(model: &Model, viscous: bool) -> u64 {
    let nodes = model.num_nodes() as u64;
    let vectors = if viscous { 4 } else { 3 };
    24 * vectors * nodes + 4
}

impl OnDevice {
    /// Uploads `model` and the joint `history` to `gpu`.
    pub(crate) fn new(gpu: &Gpu, model: &Model, history: &[JointHistory]) -> Result<OnDevice, GpuError> {
        let material: Vec<Option<u16>> = model
            .tet_material
            .iter()
            .map(|m| m.index().map(|i| u16::try_from(i).expect("TetMaterial holds a u16")))
            .collect();
        let bulk = Bulk::new(
            gpu,
            TetMesh {
                tets: &model.tets,
                refs: &model.tet_ref,
                material: &material,
                materials: &model.materials,
                num_nodes: model.num_nodes(),
                gather_offsets: &model.tet_gather.offsets,
                gather_slots: &model.tet_gather.slots,
            },
            JointMesh {
                joints: &model.joints,
                law: &model.joint_law,
                history,
                gather_offsets: &model.joint_gather.offsets,
                gather_slots: &model.joint_gather.slots,
            },
        )?;
        Ok(OnDevice {
            bulk,
            adapter: gpu.adapter(),
            synced: true,
            edited: false,
            resident: false,
            listed: Vec::new(),
            flagged: Vec::new(),
            touched: Vec::new(),
            watched: Vec::new(),
            back: femdem_gpu::Resident::default(),
        })
    }

    /// Keeps positions and velocities on the device from now on: `setup`
    /// for the update, `x`, `v`, `v_before` the state to start from;
    /// `contact` adds the host's contact forces to the update.
    pub(crate) fn make_resident(
        &mut self,
        setup: MotionSetup<'_>,
        x: &[Vec3],
        v: &[Vec3],
        v_before: &[Vec3],
        contact: bool,
    ) -> Result<(), GpuError> {
        self.bulk.enable_motion(setup)?;
        if contact {
            self.bulk.enable_contact_forces()?;
        }
        self.listed = setup.listed.to_vec();
        self.bulk.set_state(x, v);
        if !v_before.is_empty() {
            self.bulk.set_before(v_before);
        }
        self.resident = true;
        Ok(())
    }

    /// Sends the host's state up if the host changed it since the last
    /// step ([`OnDevice::edited`]); returns whether it did.
    pub(crate) fn push_if_edited(&mut self, state: &State, v_before: &[Vec3]) -> bool {
        if !self.edited {
            return false;
        }
        self.bulk.set_history(&state.joints);
        if self.resident {
            self.bulk.set_state(&state.x, &state.v);
            if !v_before.is_empty() {
                self.bulk.set_before(v_before);
            }
        }
        self.edited = false;
        self.synced = true;
        true
    }

    /// Brings everything the device holds of the state back to the host.
    pub(crate) fn pull_all(&mut self, state: &mut State, v_before: &mut [Vec3], internal: &mut [Vec3]) {
        if self.synced {
            return;
        }
        state.joints.copy_from_slice(&self.bulk.joint_history());
        if self.resident {
            self.pull_motion(state);
            if !v_before.is_empty() {
                v_before.copy_from_slice(&self.bulk.velocities_before());
            }
            internal.copy_from_slice(&self.bulk.internal());
        }
        self.synced = true;
    }

    /// Puts the joints that failed in the last evaluation into `failed_now`
    /// (clearing the entries the evaluation before set) and returns how
    /// many; `any` false (the count read back with something else was 0)
    /// reads nothing.
    pub(crate) fn take_failures(&mut self, failed_now: &mut [Option<FailureMode>], any: bool) -> usize {
        for &j in &self.flagged {
            failed_now[j as usize] = None;
        }
        self.flagged.clear();
        if any {
            for (j, mode) in self.bulk.failures() {
                failed_now[j as usize] = Some(mode);
                self.flagged.push(j);
            }
        }
        self.flagged.len()
    }

    /// The histories of the joints the last step flagged as failed, into
    /// `joints` (contact reads a failed joint's compression energy).
    pub(crate) fn pull_failed_histories(&self, joints: &mut [JointHistory]) {
        for (&j, h) in self.flagged.iter().zip(self.bulk.joint_histories_of(&self.flagged)) {
            joints[j as usize] = h;
        }
    }

    /// Resident: positions and velocities back to the host.
    pub(crate) fn pull_motion(&mut self, state: &mut State) {
        state.x.copy_from_slice(&self.bulk.positions());
        state.v.copy_from_slice(&self.bulk.velocities());
    }

    /// [`crate::forces::internal_forces`] on the device: fills
    /// `ws.internal`, `ws.failed_now` and (with `want.stress`) `ws.stress`,
    /// and returns the same sums.
    pub(crate) fn internal_forces(
        &mut self,
        x: &[Vec3],
        v: &[Vec3],
        ws: &mut Workspace,
        want: Want,
        dissipation: Dissipation<'_>,
    ) -> ForceSums {
        self.bulk.set_state(x, v);
        let viscous = if let Dissipation::Since(before) = dissipation {
            self.bulk.set_before(before);
            true
        } else {
            false
        };
        self.bulk.forces(Evaluate { stress: want.stress, energy: want.energy, dissipation: viscous });
        self.synced = false;
        ws.internal.copy_from_slice(&self.bulk.internal());
        if want.stress {
            ws.stress.copy_from_slice(&self.bulk.stresses());
        }
        let newly_failed = self.take_failures(&mut ws.failed_now, true);
        let mut sums = ForceSums { newly_failed, ..ForceSums::default() };
        if want.energy {
            sums.tet_energy = chunked(&self.bulk.tet_energies(), |&e| e);
            let joints = self.bulk.joint_sums();
            sums.joint_energy = chunked(&joints, |s| s[0]);
            sums.fracture = chunked(&joints, |s| s[1]);
        }
        if viscous {
            sums.dissipation_rate = chunked(&self.bulk.tet_rates(), |&r| if r.is_finite() { r } else { 0.0 });
        }
        sums
    }
}

/// `Σ_chunks Σ_{k in chunk} f(item_k)`, chunks of [`CHUNK`] summed in
/// order from zero and then added in order: the CPU pass's order.
fn chunked<T>(items: &[T], f: impl Fn(&T) -> Real) -> Real {
    items.chunks(CHUNK).map(|c| c.iter().fold(0.0, |a, x| a + f(x))).fold(0.0, |a, c| a + c)
}

/// How much of the step a device takes ([`crate::Solver::use_device`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Residency {
    /// Stages 1 and 5, the surface loads and the sums (positions and
    /// velocities stay on the device, the host reads the drives' nodes, the
    /// sums and the failures each step, and the positions and velocities
    /// on steps that ask for stresses or energies or have failures:
    /// `step/resident.rs`).
    Auto,
    /// Stage 1 alone (tets, joints, gather): positions and velocities go up
    /// and forces come down every step.
    ForcesOnly,
}

impl crate::Solver {
    /// Runs the step on `gpu` from the next step on, as much of it as
    /// `residency` allows ([`Residency`]); the rest stays on the CPU.
    /// Results agree with the CPU's to round-off (`femdem-gpu`'s tests;
    /// on lavapipe the joints are the CPU's bit for bit).
    ///
    /// With contact ([`Solver::enable_contact`] first), the contact pass
    /// stays on the CPU (detection, pair forces, friction, its account):
    /// resident, each step reads back the positions and velocities of the
    /// contactable tets' nodes before it, sends the contact forces of the
    /// nodes the pass touches (now or at the pass before) down, and reads
    /// those nodes' new positions and velocities back after the update.
    ///
    /// # Errors
    /// A model the device cannot hold ([`SolverError::Device`]).
    pub fn use_device(&mut self, gpu: &Gpu, residency: Residency) -> Result<(), SolverError> {
        self.sync_device();
        let device = OnDevice::new(gpu, &self.scene.model, &self.evolving.state.joints)
            .map_err(|e| SolverError::Device(e.to_string()))?;
        self.pipeline.device = Some(device);
        if residency == Residency::Auto
            && let Err(e) = self.make_resident()
        {
            // All or nothing: no half-attached device stays behind.
            self.pipeline.device = None;
            return Err(SolverError::Device(e.to_string()));
        }
        Ok(())
    }

    /// The adapter the step runs on, or `None` on the CPU.
    pub fn device(&self) -> Option<&str> {
        self.pipeline.device.as_ref().map(|d| d.adapter.as_str())
    }

    /// The adapter and the stages it runs, `adapter: stages` (`None` on the
    /// CPU): what a run's summary and history header say.
    pub fn device_summary(&self) -> Option<String> {
        self.device().zip(self.device_stages()).map(|(a, s)| format!("{a}: {s}"))
    }

    /// Which stages run on the device (`None` on the CPU).
    pub fn device_stages(&self) -> Option<&'static str> {
        self.pipeline.device.as_ref().map(|d| {
            let contact = self.evolving.contact.as_ref();
            if d.resident && contact.is_some_and(Contact::geometry_elsewhere) {
                "stages 1 and 5 (tets, joints, gather, surface loads, update, the energy sums) and the contact pairs' \
                 Eq. 17; failures, the rest of contact, drives and the account on the CPU"
            } else if d.resident && contact.is_some() {
                "stages 1 and 5 (tets, joints, gather, surface loads, update, the energy sums); failures, contact, \
                 drives and the account on the CPU"
            } else if d.resident {
                "stages 1 and 5 (tets, joints, gather, surface loads, update, the energy sums); failures, drives and \
                 the account on the CPU"
            } else {
                "stage 1 (tets, joints, gather); the rest on the CPU"
            }
        })
    }

    /// Bytes the last step moved between host and device (the arrays;
    /// each dispatch also sends 16 bytes of parameters), or 0 on the CPU;
    /// with contact it changes from step to step with the pairs asked for
    /// and the nodes touched. Output steps read back positions, velocities
    /// and stresses on top, and a step with failures the failed joints,
    /// positions and velocities.
    pub fn device_bytes_per_step(&self) -> u64 {
        match &self.pipeline.device {
            None => 0,
            Some(d) if d.resident => {
                // Failure count, the seven sums and each surface load's
                // five, the drives' nodes' state, the watched nodes'
                // positions and velocities, the pairs the last pass asked
                // the device for up (8 bytes, 8 more for the threshold) and
                // their contacts back (240) with the potential model, the touched nodes' contact forces down (28 bytes
                // each) and state back (48), the drive and surface-load
                // tables and the step's scalars.
                let surfaces = self.scene.loads.surfaces.len() as u64;
                let pairs = self.evolving.contact.as_ref().map_or(0, Contact::geometry_bytes) as u64;
                4 + 56
                    + pairs
                    + 40 * surfaces
                    + 96 * d.listed.len() as u64
                    + 48 * d.watched.len() as u64
                    + 76 * d.touched.len() as u64
                    + 32 * self.scene.loads.drives.len() as u64
                    + 48 * surfaces
                    + 16
            }
            Some(_) => bytes_per_step(&self.scene.model, self.scene.viscous),
        }
    }

    /// Where the device's step time goes ([`femdem_gpu::Bulk::timings`],
    /// `reps` repetitions each), for benchmarks: `None` on the CPU. Call it
    /// between steps: the kernels run again on the current state, which
    /// they leave as it was (positions, velocities, joint histories).
    pub fn device_timings(&mut self, reps: usize) -> Option<Vec<femdem_gpu::Timing>> {
        self.pipeline.device.as_mut().map(|d| {
            // What the device holds is read afresh by the next sync (it
            // should be what it was: the timings restore it).
            d.synced = false;
            d.bulk.timings(reps)
        })
    }

    /// The host's time around each kind of the device's read-backs since
    /// the last call (`femdem_gpu::Gpu::take_transfers`), for benchmarks;
    /// `None` on the CPU.
    pub fn device_transfers(&self) -> Option<Vec<femdem_gpu::Phase>> {
        self.pipeline.device.as_ref().map(|d| d.bulk.gpu().take_transfers())
    }

    /// Brings the state the device holds (joint histories; resident, also
    /// positions, velocities and the velocities of the step before) back
    /// into [`Solver::state`] (nothing to do on the CPU). A snapshot needs
    /// it.
    pub fn sync_device(&mut self) {
        if let Some(device) = &mut self.pipeline.device {
            let e = &mut self.evolving;
            device.pull_all(&mut e.state, &mut e.v_before, &mut self.pipeline.workspace.internal);
        }
    }

    /// Before the host changes the state between steps: brings it back
    /// from the device, and has it sent up again before the next step.
    pub(crate) fn edit_on_host(&mut self) {
        self.sync_device();
        if let Some(device) = &mut self.pipeline.device {
            device.edited = true;
        }
    }
}
