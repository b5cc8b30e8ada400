//! The bulk of the step on the device: the tet pass (Eq. 1–2) and the
//! gather into nodal forces, over arrays that stay on the device between
//! calls.
//!
//! The layout follows the CPU solver's (`femdem_solver::forces`): every
//! tet writes its own four force slots, and each node sums its slots in a
//! fixed order (tet slots, then joint slots, each in increasing order), so
//! there are no atomics and two runs give the same bytes.

use femdem_core::{Mat3, Real, Vec3};
use femdem_material::{Law, Material, TetReference};

use crate::buffers::{Params, dispatch, read, storage, write, zeroed};
use crate::device::{Gpu, GpuError};
use crate::kernels;

/// Material index of a rigid tet in the device's table.
const RIGID: u32 = u32::MAX;

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
    gpu: Gpu,
    tets_kernel: wgpu::ComputePipeline,
    gather_kernel: wgpu::ComputePipeline,
    num_tets: usize,
    num_nodes: usize,
    x: wgpu::Buffer,
    v: wgpu::Buffer,
    tets: wgpu::Buffer,
    refs: wgpu::Buffer,
    tet_mat: wgpu::Buffer,
    materials: wgpu::Buffer,
    tet_slots: wgpu::Buffer,
    energy: wgpu::Buffer,
    stress: wgpu::Buffer,
    tet_offsets: wgpu::Buffer,
    tet_table: wgpu::Buffer,
    joint_slots: wgpu::Buffer,
    joint_offsets: wgpu::Buffer,
    joint_table: wgpu::Buffer,
    internal: wgpu::Buffer,
}

/// `[x, y, z, x, y, z, …]` of a slice of vectors.
fn flat(v: &[Vec3]) -> Vec<Real> {
    v.iter().flat_map(|p| [p.x, p.y, p.z]).collect()
}

fn count(n: usize) -> u32 {
    u32::try_from(n).expect("at most 2^32 items per kernel")
}

impl Bulk {
    /// Uploads `mesh` (nodes at rest at the origin until [`Bulk::set_state`]).
    pub fn new(gpu: &Gpu, mesh: TetMesh<'_>) -> Result<Bulk, GpuError> {
        let n = mesh.tets.len();
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
            gather_kernel: gpu.pipeline("gather", &gather_module)?,
            num_tets: n,
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
            tet_offsets: storage(gpu, "tet gather offsets", mesh.gather_offsets)?,
            tet_table: storage(gpu, "tet gather slots", mesh.gather_slots)?,
            joint_slots: zeroed::<Real>(gpu, "joint slots", 0)?,
            joint_offsets: zeroed::<u32>(gpu, "joint gather offsets", mesh.num_nodes + 1)?,
            joint_table: zeroed::<u32>(gpu, "joint gather slots", 0)?,
            internal: zeroed::<Real>(gpu, "internal forces", nodes3)?,
            gpu: gpu.clone(),
        })
    }

    /// Uploads positions and velocities.
    pub fn set_state(&mut self, x: &[Vec3], v: &[Vec3]) {
        assert_eq!(x.len(), self.num_nodes, "one position per node");
        assert_eq!(v.len(), self.num_nodes, "one velocity per node");
        write(&self.gpu, &self.x, &flat(x));
        write(&self.gpu, &self.v, &flat(v));
    }

    /// Runs the tet pass (keeping each tet's Cauchy stress when `stress`)
    /// and the gather.
    pub fn forces(&mut self, stress: bool) {
        let gpu = &self.gpu;
        let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        let flags = u32::from(stress);
        dispatch(
            gpu,
            &mut encoder,
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
            ],
        );
        dispatch(
            gpu,
            &mut encoder,
            &self.gather_kernel,
            Params { count: count(self.num_nodes), flags: 0, pad: [0; 2] },
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
        gpu.queue.submit([encoder.finish()]);
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

    /// Each tet's Cauchy stress of the last [`Bulk::forces`] that asked for
    /// it (read back).
    pub fn stresses(&self) -> Vec<Mat3> {
        let s: Vec<Real> = read(&self.gpu, &self.stress, 9 * self.num_tets);
        s.chunks_exact(9).map(Mat3::from_column_slice).collect()
    }
}
