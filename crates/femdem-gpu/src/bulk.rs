//! The bulk of the step on the device: the tet pass (Eq. 1–2) and the
//! gather into nodal forces, over arrays that stay on the device between
//! calls.
//!
//! The layout follows the CPU solver's (`femdem_solver::forces`): every
//! tet writes its own four force slots, and each node sums its slots in a
//! fixed order (tet slots, then joint slots, each in increasing order), so
//! there are no atomics and two runs give the same bytes.

use femdem_core::{Mat3, Real, Vec3};
use femdem_fracture::{FailureMode, JointHistory};
use femdem_material::{Law, Material, TetReference};

use crate::buffers::{Groups, Params, dispatch, read, read_words, storage, submit_and_read, write, zeroed};
use crate::device::{Gpu, GpuError};
use crate::joints::{HISTORY, JointMesh, LAW, mode, pack_history, pack_law, rows, unpack_history};
use crate::kernels;

/// Material index of a rigid tet in the device's table.
const RIGID: u32 = u32::MAX;

/// What [`Bulk::forces`] computes besides the forces.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Evaluate {
    /// Each tet's Cauchy stress.
    pub stress: bool,
    /// Each tet's and joint's stored energy, and each joint's share of the
    /// fracture energy.
    pub energy: bool,
    /// Each tet's viscous dissipation rate against the velocities of
    /// [`Bulk::set_before`] (`femdem_solver::forces::Dissipation`).
    pub dissipation: bool,
}

/// What the device needs of a mesh of tets: the CPU solver's arrays.
#[derive(Clone, Copy, Debug)]
pub struct TetMesh<'a> {
    /// Nodes of each tet.
    pub tets: &'a [[u32; 4]],
    /// Reference shape of each tet.
    pub refs: &'a [TetReference],
    /// Index into `materials` of each tet; `None` for a rigid tet (no
    /// forces, no energy).
    pub material: &'a [Option<u16>],
    /// The materials and their laws.
    pub materials: &'a [(Law, Material)],
    /// Number of nodes.
    pub num_nodes: usize,
    /// Node-to-slot table of the tets in compressed rows: node `i`'s slots
    /// (`4 tet + local`) are `gather_slots[gather_offsets[i]..gather_offsets[i + 1]]`,
    /// increasing.
    pub gather_offsets: &'a [u32],
    /// See `gather_offsets`.
    pub gather_slots: &'a [u32],
}

/// The device's copy of a tet mesh and its state, with the two kernels.
#[derive(Debug)]
pub struct Bulk {
    pub(crate) gpu: Gpu,
    tets_kernel: wgpu::ComputePipeline,
    joints_kernel: wgpu::ComputePipeline,
    gather_kernel: wgpu::ComputePipeline,
    pub(crate) num_tets: usize,
    pub(crate) num_joints: usize,
    pub(crate) num_nodes: usize,
    pub(crate) x: wgpu::Buffer,
    pub(crate) v: wgpu::Buffer,
    pub(crate) tets: wgpu::Buffer,
    refs: wgpu::Buffer,
    tet_mat: wgpu::Buffer,
    materials: wgpu::Buffer,
    tet_slots: wgpu::Buffer,
    pub(crate) energy: wgpu::Buffer,
    stress: wgpu::Buffer,
    pub(crate) v_before: wgpu::Buffer,
    pub(crate) rate: wgpu::Buffer,
    tet_offsets: wgpu::Buffer,
    tet_table: wgpu::Buffer,
    joints: wgpu::Buffer,
    joint_law: wgpu::Buffer,
    joint_hist: wgpu::Buffer,
    joint_flags: wgpu::Buffer,
    joint_slots: wgpu::Buffer,
    pub(crate) joint_sums: wgpu::Buffer,
    joint_failed: wgpu::Buffer,
    pub(crate) failed_list: wgpu::Buffer,
    joint_consts: wgpu::Buffer,
    joint_offsets: wgpu::Buffer,
    joint_table: wgpu::Buffer,
    pub(crate) internal: wgpu::Buffer,
    /// The update's buffers, once [`Bulk::enable_motion`] has run.
    pub(crate) motion: Option<crate::motion::Motion>,
    /// The bind groups of earlier dispatches.
    pub(crate) groups: Groups,
    /// The contact pairs' kernel and buffers, once [`Bulk::pair_geometry`]
    /// has run.
    pub(crate) pair_kernel: Option<crate::pairs::PairKernel>,
    pub(crate) pair_buffers: Option<crate::pairs::PairBuffers>,
}

/// `[x, y, z, x, y, z, …]` of a slice of vectors.
fn flat(v: &[Vec3]) -> Vec<Real> {
    v.iter().flat_map(|p| [p.x, p.y, p.z]).collect()
}

fn count(n: usize) -> u32 {
    u32::try_from(n).expect("at most 2^32 items per kernel")
}

impl Bulk {
    /// Uploads the tets and joints (nodes at the origin, at rest, until
    /// [`Bulk::set_state`]).
    pub fn new(gpu: &Gpu, mesh: TetMesh<'_>, joints: JointMesh<'_>) -> Result<Bulk, GpuError> {
        let n = mesh.tets.len();
        let nj = joints.joints.len();
        assert_eq!(joints.law.len(), nj, "one law per joint");
        assert_eq!(joints.history.len(), nj, "one history per joint");
        assert_eq!(joints.gather_offsets.len(), mesh.num_nodes + 1, "one joint gather row per node");
        let joints_module = gpu.module("joints", &kernels::joints())?;
        let (hist, flags) = pack_history(joints.history);
        let consts = [femdem_fracture::KernelConsts::new().z0, femdem_fracture::softening::softening_area()];
        assert_eq!(mesh.refs.len(), n, "one reference per tet");
        assert_eq!(mesh.material.len(), n, "one material entry per tet");
        assert_eq!(mesh.gather_offsets.len(), mesh.num_nodes + 1, "one gather row per node");
        let tets_module = gpu.module("tets", &kernels::tets())?;
        let gather_module = gpu.module("gather", &kernels::gather())?;
        let refs: Vec<Real> = mesh
            .refs
            .iter()
            .flat_map(|r| r.inv_dm.iter().copied().chain(std::iter::once(r.volume)).collect::<Vec<_>>())
            .collect();
        let tet_mat: Vec<u32> = mesh.material.iter().map(|m| m.map_or(RIGID, u32::from)).collect();
        let materials: Vec<Real> = mesh
            .materials
            .iter()
            .flat_map(|(law, m)| {
                let code = match law {
                    Law::NeoHookean => 0.0,
                    Law::LinearElastic => 1.0,
                };
                [m.lambda(), m.mu(), m.viscosity(), code]
            })
            .collect();
        let nodes3 = 3 * mesh.num_nodes;
        Ok(Bulk {
            tets_kernel: gpu.pipeline("tets", &tets_module)?,
            joints_kernel: gpu.pipeline("joints", &joints_module)?,
            gather_kernel: gpu.pipeline("gather", &gather_module)?,
            num_tets: n,
            num_joints: nj,
            num_nodes: mesh.num_nodes,
            x: zeroed::<Real>(gpu, "positions", nodes3)?,
            v: zeroed::<Real>(gpu, "velocities", nodes3)?,
            tets: storage(gpu, "tet nodes", mesh.tets.as_flattened())?,
            refs: storage(gpu, "tet references", &refs)?,
            tet_mat: storage(gpu, "tet materials", &tet_mat)?,
            materials: storage(gpu, "materials", &materials)?,
            tet_slots: zeroed::<Real>(gpu, "tet slots", 12 * n)?,
            energy: zeroed::<Real>(gpu, "tet energies", n)?,
            stress: zeroed::<Real>(gpu, "tet stresses", 9 * n)?,
            v_before: zeroed::<Real>(gpu, "velocities of the step before", nodes3)?,
            rate: zeroed::<Real>(gpu, "tet dissipation rates", n)?,
            tet_offsets: storage(gpu, "tet gather offsets", mesh.gather_offsets)?,
            tet_table: storage(gpu, "tet gather slots", mesh.gather_slots)?,
            joints: storage(gpu, "joint nodes", joints.joints.as_flattened())?,
            joint_law: storage(gpu, "joint laws", &pack_law(joints.law))?,
            joint_hist: storage(gpu, "joint histories", &hist)?,
            joint_flags: storage(gpu, "joint flags", &flags)?,
            joint_slots: zeroed::<Real>(gpu, "joint slots", 18 * nj)?,
            joint_sums: zeroed::<Real>(gpu, "joint sums", 2 * nj)?,
            joint_failed: zeroed::<u32>(gpu, "joint failures", nj)?,
            failed_list: zeroed::<u32>(gpu, "failed joints", nj + 1)?,
            joint_consts: storage(gpu, "joint constants", &consts)?,
            joint_offsets: storage(gpu, "joint gather offsets", joints.gather_offsets)?,
            joint_table: storage(gpu, "joint gather slots", joints.gather_slots)?,
            internal: zeroed::<Real>(gpu, "internal forces", nodes3)?,
            motion: None,
            groups: Groups::default(),
            pair_kernel: None,
            pair_buffers: None,
            gpu: gpu.clone(),
        })
    }

    /// The device this model lives on.
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }

    /// Uploads positions and velocities.
    pub fn set_state(&mut self, x: &[Vec3], v: &[Vec3]) {
        assert_eq!(x.len(), self.num_nodes, "one position per node");
        assert_eq!(v.len(), self.num_nodes, "one velocity per node");
        write(&self.gpu, &self.x, &flat(x));
        write(&self.gpu, &self.v, &flat(v));
    }

    /// Uploads the velocities of the step before, `v_{n−3/2}`, for the
    /// dissipation rate ([`Evaluate::dissipation`]).
    pub fn set_before(&mut self, v_before: &[Vec3]) {
        assert_eq!(v_before.len(), self.num_nodes, "one velocity per node");
        write(&self.gpu, &self.v_before, &flat(v_before));
    }

    /// Runs the tet pass, the joint pass and the gather, with what `want`
    /// asks for besides the forces.
    pub fn forces(&mut self, want: Evaluate) {
        let mut encoder = self.gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        self.encode_forces(&mut encoder, want);
        self.gpu.queue.submit([encoder.finish()]);
    }

    /// [`Bulk::forces`]'s passes, recorded into `encoder`.
    pub(crate) fn encode_forces(&self, encoder: &mut wgpu::CommandEncoder, want: Evaluate) {
        self.encode_tets(encoder, want);
        self.encode_joints(encoder, want.energy);
        self.encode_gather(encoder);
    }

    /// The tet pass (`wgsl/tets.wgsl`), recorded into `encoder`.
    pub(crate) fn encode_tets(&self, encoder: &mut wgpu::CommandEncoder, want: Evaluate) {
        let flags = u32::from(want.stress) | u32::from(want.dissipation) << 1;
        dispatch(
            &self.gpu,
            Some(&self.groups),
            encoder,
            &self.tets_kernel,
            Params { count: count(self.num_tets), flags, pad: [0; 2] },
            &[
                &self.x,
                &self.v,
                &self.tets,
                &self.refs,
                &self.tet_mat,
                &self.materials,
                &self.tet_slots,
                &self.energy,
                &self.stress,
                &self.v_before,
                &self.rate,
            ],
        );
    }

    /// The joint pass (`wgsl/joints.wgsl`), with each joint's energies if
    /// `energy`, recorded into `encoder` (nothing without joints).
    pub(crate) fn encode_joints(&self, encoder: &mut wgpu::CommandEncoder, energy: bool) {
        if self.num_joints == 0 {
            return;
        }
        encoder.clear_buffer(&self.failed_list, 0, Some(4));
        dispatch(
            &self.gpu,
            Some(&self.groups),
            encoder,
            &self.joints_kernel,
            Params { count: count(self.num_joints), flags: u32::from(energy), pad: [0; 2] },
            &[
                &self.x,
                &self.joints,
                &self.joint_law,
                &self.joint_hist,
                &self.joint_flags,
                &self.joint_slots,
                &self.joint_sums,
                &self.joint_failed,
                &self.joint_consts,
                &self.failed_list,
            ],
        );
    }

    /// The buffers a joint pass changes besides its slots and sums: the
    /// histories, flags, failure words and failure list (what
    /// [`Bulk::timings`] saves and restores).
    pub(crate) fn joint_state(&self) -> [&wgpu::Buffer; 4] {
        [&self.joint_hist, &self.joint_flags, &self.joint_failed, &self.failed_list]
    }

    /// The gather (`wgsl/gather.wgsl`), recorded into `encoder`.
    pub(crate) fn encode_gather(&self, encoder: &mut wgpu::CommandEncoder) {
        dispatch(
            &self.gpu,
            Some(&self.groups),
            encoder,
            &self.gather_kernel,
            Params { count: count(self.num_nodes), flags: 0, pad: [count(self.num_joints), 0] },
            &[
                &self.tet_slots,
                &self.tet_offsets,
                &self.tet_table,
                &self.joint_slots,
                &self.joint_offsets,
                &self.joint_table,
                &self.internal,
            ],
        );
    }

    /// The gathered internal force on every node (read back).
    pub fn internal(&self) -> Vec<Vec3> {
        let f: Vec<Real> = read(&self.gpu, &self.internal, 3 * self.num_nodes);
        f.chunks_exact(3).map(|c| Vec3::new(c[0], c[1], c[2])).collect()
    }

    /// Each tet's forces on its four nodes (read back).
    pub fn tet_slots(&self) -> Vec<[Vec3; 4]> {
        let f: Vec<Real> = read(&self.gpu, &self.tet_slots, 12 * self.num_tets);
        f.chunks_exact(12).map(|c| std::array::from_fn(|k| Vec3::new(c[3 * k], c[3 * k + 1], c[3 * k + 2]))).collect()
    }

    /// Each tet's stored energy `W V₀`, J (read back).
    pub fn tet_energies(&self) -> Vec<Real> {
        read(&self.gpu, &self.energy, self.num_tets)
    }

    /// Each tet's viscous dissipation rate of the last [`Bulk::forces`]
    /// that asked for it, W (read back; zero for the others).
    pub fn tet_rates(&self) -> Vec<Real> {
        read(&self.gpu, &self.rate, self.num_tets)
    }

    /// Each tet's Cauchy stress of the last [`Bulk::forces`] that asked for
    /// it (read back).
    pub fn stresses(&self) -> Vec<Mat3> {
        let s: Vec<Real> = read(&self.gpu, &self.stress, 9 * self.num_tets);
        s.chunks_exact(9).map(Mat3::from_column_slice).collect()
    }
}

impl Bulk {
    /// Each joint's forces on its six nodes (read back).
    pub fn joint_slots(&self) -> Vec<[Vec3; 6]> {
        let n = self.num_joints;
        let f: Vec<Real> = read(&self.gpu, &self.joint_slots, 18 * n);
        let at = |j: usize, k: usize| f[k * n + j];
        (0..n).map(|j| std::array::from_fn(|k| Vec3::new(at(j, 3 * k), at(j, 3 * k + 1), at(j, 3 * k + 2)))).collect()
    }

    /// Overwrites every joint's history (after the host changed it: joints
    /// broken by decree, a restored checkpoint).
    pub fn set_history(&mut self, history: &[JointHistory]) {
        assert_eq!(history.len(), self.num_joints, "one history per joint");
        let (numbers, flags) = pack_history(history);
        write(&self.gpu, &self.joint_hist, &numbers);
        write(&self.gpu, &self.joint_flags, &flags);
    }

    /// Each joint's history (read back).
    pub fn joint_history(&self) -> Vec<JointHistory> {
        let numbers: Vec<Real> = read(&self.gpu, &self.joint_hist, HISTORY * self.num_joints);
        let flags: Vec<u32> = read(&self.gpu, &self.joint_flags, self.num_joints);
        unpack_history(&rows(&numbers, self.num_joints, HISTORY), &flags)
    }

    /// The histories of joints `joints` (read back in one submission).
    pub fn joint_histories_of(&self, joints: &[u32]) -> Vec<JointHistory> {
        if joints.is_empty() {
            return Vec::new();
        }
        let encoder = self.gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        // Each joint's 24 numbers (one word apart by the joints' count),
        // then its flags.
        let n = self.num_joints as u64;
        let copies: Vec<_> = joints
            .iter()
            .flat_map(|&j| {
                let j = u64::from(j);
                (0..HISTORY as u64).map(move |k| (&self.joint_hist, 8 * (k * n + j), 8)).chain(std::iter::once((
                    &self.joint_flags,
                    4 * j,
                    4,
                )))
            })
            .collect();
        let bytes = submit_and_read(&self.gpu, encoder, &copies);
        let rows = bytes.chunks_exact(HISTORY + 1);
        let numbers: Vec<Real> = rows
            .clone()
            .flat_map(|r| r[..HISTORY].iter().map(|b| Real::from_le_bytes(b[..8].try_into().expect("8 bytes"))))
            .collect();
        let flags: Vec<u32> = rows.map(|r| u32::from_le_bytes(r[HISTORY][..4].try_into().expect("4 bytes"))).collect();
        unpack_history(&numbers, &flags)
    }

    /// The joints that failed in the last evaluation and how, in joint
    /// order (reads back one word, and two per failed joint).
    pub fn failures(&self) -> Vec<(u32, FailureMode)> {
        if self.num_joints == 0 {
            return Vec::new();
        }
        let count = read::<u32>(&self.gpu, &self.failed_list, 1)[0] as usize;
        if count == 0 {
            return Vec::new();
        }
        let mut joints: Vec<u32> = read::<u32>(&self.gpu, &self.failed_list, count + 1)[1..].to_vec();
        joints.sort_unstable();
        let words = read_words(&self.gpu, &self.joint_failed, &joints);
        joints.into_iter().zip(words).map(|(j, w)| (j, mode(w).expect("a failed joint has a mode"))).collect()
    }

    /// How each joint that failed in the last evaluation failed (read back).
    pub fn failed_now(&self) -> Vec<Option<FailureMode>> {
        read::<u32>(&self.gpu, &self.joint_failed, self.num_joints).into_iter().map(mode).collect()
    }

    /// Each joint's stored energy and share of the fracture energy (its
    /// work, less what it stores while intact) of the last evaluation that
    /// asked for energies, J (read back).
    pub fn joint_sums(&self) -> Vec<[Real; 2]> {
        read::<Real>(&self.gpu, &self.joint_sums, 2 * self.num_joints).chunks_exact(2).map(|c| [c[0], c[1]]).collect()
    }
}

const _: () = assert!(LAW == 10 && HISTORY == 24, "the layouts of wgsl/joints.wgsl");
