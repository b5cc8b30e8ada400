//! The bulk of the step on a GPU: stage 1 (the tet pass of Eq. 1–2, the
//! joint pass of Eq. 3–13 and the gather) run by `femdem-gpu`, the rest of
//! the step (failures, external forces, the update, the ledger) on the CPU
//! as before ([`Solver::use_device`](crate::Solver::use_device)).
//!
//! Each step uploads the positions and velocities (and, with viscous
//! materials, the velocities of the step before) and reads back the
//! gathered internal forces and which joints failed; the stresses, the
//! per-element energies and dissipation rates only on the steps that ask
//! for them. The joint histories live on the device: [`State::joints`]
//! is brought up to date by [`Solver::sync_device`](crate::Solver::sync_device).
//! The energy sums are taken on the host from the per-element values in
//! the CPU pass's chunk order, so equal element values give equal sums.
//!
//! [`State::joints`]: crate::State::joints

use femdem_core::{Real, Vec3};
use femdem_fracture::JointHistory;
use femdem_gpu::{Bulk, Evaluate, Gpu, GpuError, JointMesh, TetMesh};

use crate::SolverError;
use crate::forces::{CHUNK, Dissipation, ForceSums, Want, Workspace};
use crate::model::Model;

/// The device's copy of the model and its joint histories.
pub(crate) struct OnDevice {
    bulk: Bulk,
    /// The adapter's name.
    pub(crate) adapter: String,
    /// Whether the host's joint histories are the device's.
    pub(crate) synced: bool,
}

/// Bytes one step moves between host and device at least: positions and
/// velocities up, internal forces down (24 bytes a node each), the
/// velocities of the step before up with viscous materials, and the
/// failure word of every joint down.
pub(crate) fn bytes_per_step(model: &Model, viscous: bool) -> u64 {
    let nodes = model.num_nodes() as u64;
    let vectors = if viscous { 4 } else { 3 };
    24 * vectors * nodes + 4 * model.joints.len() as u64
}

impl OnDevice {
    /// Uploads `model` and the joint `history` to `gpu`.
    pub(crate) fn new(gpu: &Gpu, model: &Model, history: &[JointHistory]) -> Result<OnDevice, GpuError> {
        let material: Vec<Option<u16>> = model.tet_material.iter().map(|m| m.index().map(|i| i as u16)).collect();
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
        Ok(OnDevice { bulk, adapter: gpu.adapter(), synced: true })
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
        ws.failed_now.copy_from_slice(&self.bulk.failed_now());
        if want.stress {
            ws.stress.copy_from_slice(&self.bulk.stresses());
        }
        let mut sums =
            ForceSums { newly_failed: ws.failed_now.iter().filter(|f| f.is_some()).count(), ..ForceSums::default() };
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

    /// Copies the device's joint histories into `history`.
    pub(crate) fn pull(&mut self, history: &mut [JointHistory]) {
        history.copy_from_slice(&self.bulk.joint_history());
        self.synced = true;
    }

    /// Replaces the device's joint histories by `history`.
    pub(crate) fn push(&mut self, history: &[JointHistory]) {
        self.bulk.set_history(history);
        self.synced = true;
    }
}

/// `Σ_chunks Σ_{k in chunk} f(item_k)`, chunks of [`CHUNK`] summed in
/// order from zero and then added in order: the CPU pass's order.
fn chunked<T>(items: &[T], f: impl Fn(&T) -> Real) -> Real {
    items.chunks(CHUNK).map(|c| c.iter().fold(0.0, |a, x| a + f(x))).fold(0.0, |a, c| a + c)
}

impl crate::Solver {
    /// Runs stage 1 of every later step (tets, joints, gather) on `gpu`;
    /// the rest of the step stays on the CPU. Results agree with the CPU's
    /// to round-off (`femdem-gpu`'s tests; on lavapipe they are the CPU's
    /// bit for bit).
    ///
    /// # Errors
    /// A solver with contact ([`SolverError::Device`]: contact on the
    /// device is not built), or a model the device cannot hold.
    pub fn use_device(&mut self, gpu: &Gpu) -> Result<(), SolverError> {
        if self.evolving.contact.is_some() {
            return Err(SolverError::Device(format!(
                "{}: contact runs on the CPU only (contact on the device is not built yet); run this case on the CPU",
                gpu.adapter()
            )));
        }
        let device = OnDevice::new(gpu, &self.scene.model, &self.evolving.state.joints)
            .map_err(|e| SolverError::Device(e.to_string()))?;
        self.pipeline.device = Some(device);
        Ok(())
    }

    /// The adapter stage 1 runs on, or `None` on the CPU.
    pub fn device(&self) -> Option<&str> {
        self.pipeline.device.as_ref().map(|d| d.adapter.as_str())
    }

    /// Bytes a step moves between host and device at least (positions and
    /// velocities up, internal forces and failures down), or 0 on the CPU;
    /// output steps read back stresses and energies on top.
    pub fn device_bytes_per_step(&self) -> u64 {
        if self.pipeline.device.is_some() { bytes_per_step(&self.scene.model, self.scene.viscous) } else { 0 }
    }

    /// Brings the joint histories of [`Solver::state`] up to date with the
    /// device's (nothing to do on the CPU). A snapshot needs it.
    pub fn sync_device(&mut self) {
        if let Some(device) = &mut self.pipeline.device {
            if !device.synced {
                device.pull(&mut self.evolving.state.joints);
            }
        }
    }
}
