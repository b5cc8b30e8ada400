//! The rest of a step on the device, for scenes without surface loads or
//! contact: the update (`wgsl/update.wgsl`), the sums the energy account
//! takes (`wgsl/reduce.wgsl`, in the CPU's chunk order), and the listed
//! nodes' state the host needs for the drives (`wgsl/compact.wgsl`). With
//! these, positions and velocities stay on the device between steps.

use femdem_core::{Real, Vec3};

use crate::buffers::{Params, dispatch, read, storage, submit_and_read, write, zeroed};
use crate::bulk::Bulk;
use crate::bulk::Evaluate;
use crate::device::{Gpu, GpuError};
use crate::kernels;

/// Items per chunk of the CPU's parallel passes (`femdem_solver::forces::CHUNK`).
pub const CHUNK: usize = 512;

/// What the update needs of the scene.
#[derive(Clone, Copy, Debug)]
pub struct MotionSetup<'a> {
    /// Lumped mass of each node, kg (0 for a node of a rigid body).
    pub mass: &'a [Real],
    /// Each node's weight, N (gravity times its physical mass).
    pub weight: &'a [Vec3],
    /// Each node's three components: 0 free, 1 fixed, `2 + d` driven by
    /// drive `d`.
    pub claims: &'a [[u32; 3]],
    /// How many drives there are.
    pub drives: usize,
    /// The nodes whose state the host reads every step ([`Bulk::listed`]).
    pub listed: &'a [u32],
}

/// A sum [`Bulk::sum`] can take, and where [`Bulk::totals`] returns it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sum {
    /// Σ w · v_{n−½} (gravity's power against the old velocities).
    WeightBack = 0,
    /// Σ w · v_{n+½}.
    WeightAhead = 1,
    /// Σ ½ m v_{n−½} · v_{n+½}.
    Kinetic = 2,
    /// Σ of the tets' stored energies.
    TetEnergy = 3,
    /// Σ of the joints' stored energies.
    JointEnergy = 4,
    /// Σ of the joints' shares of the fracture energy.
    Fracture = 5,
    /// Σ of the tets' finite dissipation rates.
    Dissipation = 6,
}

/// The update's buffers and kernels.
#[derive(Debug)]
pub(crate) struct Motion {
    update_kernel: wgpu::ComputePipeline,
    reduce_kernel: wgpu::ComputePipeline,
    compact_kernel: wgpu::ComputePipeline,
    mass: wgpu::Buffer,
    weight: wgpu::Buffer,
    claims: wgpu::Buffer,
    drives: wgpu::Buffer,
    num_drives: usize,
    scalars: wgpu::Buffer,
    terms: wgpu::Buffer,
    partial: wgpu::Buffer,
    totals: wgpu::Buffer,
    listed: wgpu::Buffer,
    num_listed: usize,
    compacted: wgpu::Buffer,
}

impl Motion {
    pub(crate) fn new(
        gpu: &Gpu,
        setup: MotionSetup<'_>,
        nodes: usize,
        tets: usize,
        joints: usize,
    ) -> Result<Motion, GpuError> {
        assert_eq!(setup.mass.len(), nodes, "one mass per node");
        assert_eq!(setup.weight.len(), nodes, "one weight per node");
        assert_eq!(setup.claims.len(), nodes, "one claim triple per node");
        let update = gpu.module("update", &kernels::update())?;
        let reduce = gpu.module("reduce", &kernels::reduce())?;
        let compact = gpu.module("compact", &kernels::compact())?;
        let weight: Vec<Real> = setup.weight.iter().flat_map(|w| [w.x, w.y, w.z]).collect();
        let chunks = nodes.max(tets).max(joints).div_ceil(CHUNK);
        Ok(Motion {
            update_kernel: gpu.pipeline("update", &update)?,
            reduce_kernel: gpu.pipeline("reduce", &reduce)?,
            compact_kernel: gpu.pipeline("compact", &compact)?,
            mass: storage(gpu, "masses", setup.mass)?,
            weight: storage(gpu, "weights", &weight)?,
            claims: storage(gpu, "claims", setup.claims.as_flattened())?,
            drives: zeroed::<Real>(gpu, "drive targets", 4 * setup.drives)?,
            num_drives: setup.drives,
            scalars: zeroed::<Real>(gpu, "update scalars", 2)?,
            terms: zeroed::<Real>(gpu, "power terms", 3 * nodes)?,
            partial: zeroed::<Real>(gpu, "chunk sums", chunks)?,
            totals: zeroed::<Real>(gpu, "sums", 8)?,
            listed: storage(gpu, "listed nodes", setup.listed)?,
            num_listed: setup.listed.len(),
            compacted: zeroed::<Real>(gpu, "listed nodes' state", 9 * setup.listed.len())?,
        })
    }
}

fn count(n: usize) -> u32 {
    u32::try_from(n).expect("at most 2^32 items per kernel")
}

impl Bulk {
    /// Readies the update on the device ([`Bulk::advance`]).
    pub fn enable_motion(&mut self, setup: MotionSetup<'_>) -> Result<(), GpuError> {
        self.motion = Some(Motion::new(&self.gpu, setup, self.num_nodes, self.num_tets, self.num_joints)?);
        Ok(())
    }

    fn motion(&self) -> &Motion {
        self.motion.as_ref().expect("Bulk::enable_motion first")
    }

    /// Stage 1 ([`Bulk::forces`] with `want`), the sums `sums` of it, and
    /// the listed nodes' position, velocity and internal force, in one
    /// submission and one read-back: how many joints failed (their list:
    /// [`Bulk::failures`]) and the listed nodes' state. The sums land in
    /// the totals that [`Bulk::advance`] returns.
    pub fn forces_resident(&mut self, want: Evaluate, sums: &[Sum]) -> (u32, Vec<[Vec3; 3]>) {
        let gpu = &self.gpu;
        let m = self.motion();
        let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        self.encode_forces(&mut encoder, want);
        for &sum in sums {
            let (source, items, stride, offset, finite) = match sum {
                Sum::TetEnergy => (&self.energy, self.num_tets, 1, 0, false),
                Sum::Dissipation => (&self.rate, self.num_tets, 1, 0, true),
                Sum::JointEnergy => (&self.joint_sums, self.num_joints, 2, 0, false),
                Sum::Fracture => (&self.joint_sums, self.num_joints, 2, 1, false),
                Sum::WeightBack | Sum::WeightAhead | Sum::Kinetic => panic!("{sum:?} is taken by Bulk::advance"),
            };
            self.encode_sum(&mut encoder, source, items, stride, offset, finite, sum);
        }
        dispatch(
            gpu,
            &mut encoder,
            &m.compact_kernel,
            Params { count: count(m.num_listed), flags: 0, pad: [0; 2] },
            &[&self.x, &self.v, &self.internal, &m.listed, &m.compacted],
        );
        let failed_words = if self.num_joints > 0 { 4 } else { 0 };
        let bytes = submit_and_read(
            gpu,
            encoder,
            &[(&self.failed_list, 0, failed_words), (&m.compacted, 0, 72 * m.num_listed as u64)],
        );
        let failed = if failed_words > 0 { u32::from_le_bytes(bytes[0][..4].try_into().expect("4 bytes")) } else { 0 };
        let numbers: Vec<Real> = bytemuck::pod_collect_to_vec(&bytes[1]);
        let listed = numbers
            .chunks_exact(9)
            .map(|c| [Vec3::new(c[0], c[1], c[2]), Vec3::new(c[3], c[4], c[5]), Vec3::new(c[6], c[7], c[8])])
            .collect();
        (failed, listed)
    }

    /// The central-difference update of step `n` over `dt` with the
    /// internal forces of the last stage 1: `drives[d]` is drive `d`'s
    /// target velocity and whether it is active; `keep_before` keeps
    /// `v_{n−½}` for the next dissipation rate. Returns the sums of
    /// [`Sum`], in its order: gravity's powers and the kinetic energy of
    /// this update, and those of stage 1 that
    /// [`Bulk::forces_resident`] was asked for.
    pub fn advance(&mut self, dt: Real, drives: &[(Vec3, bool)], keep_before: bool) -> [Real; 7] {
        let gpu = &self.gpu;
        let m = self.motion();
        assert_eq!(drives.len(), m.num_drives, "one target per drive");
        let table: Vec<Real> = drives.iter().flat_map(|(t, on)| [t.x, t.y, t.z, Real::from(u8::from(*on))]).collect();
        write(gpu, &m.drives, &table);
        write(gpu, &m.scalars, &[dt, 0.0]);
        let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        dispatch(
            gpu,
            &mut encoder,
            &m.update_kernel,
            Params { count: count(self.num_nodes), flags: u32::from(keep_before), pad: [0; 2] },
            &[
                &self.x,
                &self.v,
                &self.v_before,
                &self.internal,
                &m.mass,
                &m.weight,
                &m.claims,
                &m.drives,
                &m.scalars,
                &m.terms,
            ],
        );
        for (offset, sum) in [(0, Sum::WeightBack), (1, Sum::WeightAhead), (2, Sum::Kinetic)] {
            self.encode_sum(&mut encoder, &m.terms, self.num_nodes, 3, offset, false, sum);
        }
        let bytes = submit_and_read(gpu, encoder, &[(&m.totals, 0, 56)]);
        let t: Vec<Real> = bytemuck::pod_collect_to_vec(&bytes[0]);
        std::array::from_fn(|k| t[k])
    }

    /// A two-pass sum of `input[stride k + offset]`, `k < items`, into
    /// totals slot `sum`, recorded into `encoder`.
    #[allow(clippy::too_many_arguments)]
    fn encode_sum(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        input: &wgpu::Buffer,
        items: usize,
        stride: u32,
        offset: u32,
        finite: bool,
        sum: Sum,
    ) {
        let gpu = &self.gpu;
        let m = self.motion();
        let shape = storage(gpu, "sum shape", &[stride, offset, sum as u32, 0]).expect("16 bytes fit");
        let buffers = [input, &m.partial, &m.totals, &shape];
        let chunks = items.div_ceil(CHUNK);
        let pass = |invocations, flags| Params { count: count(invocations), flags, pad: [count(items), 0] };
        dispatch(gpu, encoder, &m.reduce_kernel, pass(chunks, u32::from(finite)), &buffers);
        dispatch(gpu, encoder, &m.reduce_kernel, pass(1, 2), &buffers);
    }

    /// Every node's position (read back).
    pub fn positions(&self) -> Vec<Vec3> {
        unflat(&read(&self.gpu, &self.x, 3 * self.num_nodes))
    }

    /// Every node's velocity (read back).
    pub fn velocities(&self) -> Vec<Vec3> {
        unflat(&read(&self.gpu, &self.v, 3 * self.num_nodes))
    }

    /// Every node's velocity of the step before, as the update kept it
    /// (read back).
    pub fn velocities_before(&self) -> Vec<Vec3> {
        unflat(&read(&self.gpu, &self.v_before, 3 * self.num_nodes))
    }
}

fn unflat(f: &[Real]) -> Vec<Vec3> {
    f.chunks_exact(3).map(|c| Vec3::new(c[0], c[1], c[2])).collect()
}
