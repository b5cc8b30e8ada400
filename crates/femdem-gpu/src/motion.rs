//! The rest of a step on the device (contact, where a scene has it, is the
//! host's: its forces come down, `wgsl/scatter.wgsl`): the surface loads ([`crate::surface`]), the update (`wgsl/update.wgsl`),
//! the sums the energy account takes (`wgsl/reduce.wgsl`, in the CPU's
//! chunk order), and the listed nodes' state the host needs for the drives
//! (`wgsl/compact.wgsl`). With these, positions and velocities stay on the
//! device between steps.

use femdem_core::{Real, Vec3};

use crate::buffers::{Params, dispatch, read, reals, storage, submit_and_read_as, submit_and_read_with, write, zeroed};
use crate::bulk::Bulk;
use crate::bulk::Evaluate;
use crate::device::{Gpu, GpuError};
use crate::kernels;
use crate::surface::{LoadSums, SurfaceLoad, Surfaces, TERMS};
use crate::transfers::ReadBack;

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
    /// The nodes whose state the host reads every step
    /// ([`Bulk::forces_resident`]).
    pub listed: &'a [u32],
    /// The surface loads, in the order their factors and sums take.
    pub surfaces: &'a [SurfaceLoad<'a>],
}

/// What [`Bulk::advance`] returns: the sums of a step.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Totals {
    /// The sums of [`Sum`], in its order: gravity's powers and the kinetic
    /// energy of the update, and those of stage 1 that
    /// [`Bulk::forces_resident`] was asked for (others are stale).
    pub sums: [Real; 7],
    /// Each surface load's total force and powers, in load order.
    pub loads: Vec<LoadSums>,
    /// The positions `x_{n+1}` and velocities `v_{n+½}` after the update
    /// of the nodes [`Bulk::advance`]'s `contact` listed, in its order.
    pub contact_nodes: Vec<[Vec3; 2]>,
}

/// What [`Bulk::forces_resident`] reads back.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Resident {
    /// How many joints failed (their list: [`Bulk::failures`]).
    pub failed: u32,
    /// Each listed node's position, velocity, internal and surface-load
    /// force, in the list's order.
    pub listed: Vec<[Vec3; 4]>,
    /// Each watched node's position and velocity ([`Bulk::set_watched`]),
    /// in the list's order.
    pub watched: Vec<[Vec3; 2]>,
}

impl std::ops::Index<Sum> for Totals {
    type Output = Real;
    fn index(&self, s: Sum) -> &Real {
        &self.sums[s as usize]
    }
}

/// Slots of the totals buffer before the surface loads'.
const FIXED: usize = 7;

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

/// The nodes whose contact forces [`Bulk::advance`] sends down, their
/// forces and their new state, kept between steps.
#[derive(Debug)]
struct ContactNodes {
    nodes: wgpu::Buffer,
    forces: wgpu::Buffer,
    after: wgpu::Buffer,
    /// Nodes the buffers hold.
    capacity: usize,
}

/// The update's buffers and kernels.
#[derive(Debug)]
pub(crate) struct Motion {
    update_kernel: wgpu::ComputePipeline,
    reduce_kernel: wgpu::ComputePipeline,
    compact_kernel: wgpu::ComputePipeline,
    scatter_kernel: wgpu::ComputePipeline,
    /// Each node's contact force, N, once [`Bulk::enable_contact_forces`]
    /// has run.
    f_contact: Option<wgpu::Buffer>,
    /// The buffers of the nodes whose contact forces go down.
    contact: ContactNodes,
    mass: wgpu::Buffer,
    weight: wgpu::Buffer,
    /// Whether any node has weight: without, gravity's two powers are
    /// sums of zeros, +0 (the totals' slots stay at their zeros).
    weighed: bool,
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
    /// The nodes whose positions and velocities the host reads every
    /// step besides the listed ones, and where they are compacted.
    watched: wgpu::Buffer,
    num_watched: usize,
    watched_out: wgpu::Buffer,
    /// The reduce kernel's shape of each [`Sum`], in its order.
    shapes: Vec<wgpu::Buffer>,
    surfaces: Option<Surfaces>,
    /// The reduce kernel's shapes of each surface load's five sums (force
    /// x, y, z; back; ahead).
    load_shapes: Vec<[wgpu::Buffer; TERMS]>,
}

/// Stride and offset of each [`Sum`] in its source array.
const SHAPES: [(u32, u32); FIXED] = [(3, 0), (3, 1), (3, 2), (1, 0), (2, 0), (2, 1), (1, 0)];

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
        let scatter = gpu.module("scatter", &kernels::scatter())?;
        let weight: Vec<Real> = setup.weight.iter().flat_map(|w| [w.x, w.y, w.z]).collect();
        let surfaces = Surfaces::new(gpu, setup.surfaces, nodes)?;
        let faces = surfaces.as_ref().map_or(0, |s| s.ranges.last().map_or(0, |r| r.1));
        let chunks = nodes.max(tets).max(joints).max(faces).div_ceil(CHUNK);
        let shape = |stride: usize, offset: usize, slot: usize| {
            storage(gpu, "sum shape", &[count(stride), count(offset), count(slot), 0])
        };
        let shapes =
            SHAPES.iter().enumerate().map(|(k, &(s, o))| shape(s as usize, o as usize, k)).collect::<Result<_, _>>()?;
        let mut load_shapes = Vec::new();
        for (k, &(first, _)) in surfaces.iter().flat_map(|s| s.ranges.iter()).enumerate() {
            let one = |c: usize| shape(TERMS, TERMS * first + c, FIXED + TERMS * k + c);
            load_shapes.push([one(0)?, one(1)?, one(2)?, one(3)?, one(4)?]);
        }
        let slots = FIXED + TERMS * setup.surfaces.len();
        Ok(Motion {
            update_kernel: gpu.pipeline("update", &update)?,
            reduce_kernel: gpu.pipeline("reduce", &reduce)?,
            compact_kernel: gpu.pipeline("compact", &compact)?,
            scatter_kernel: gpu.pipeline("scatter", &scatter)?,
            f_contact: None,
            contact: ContactNodes {
                nodes: zeroed::<u32>(gpu, "contact nodes", 0)?,
                forces: zeroed::<Real>(gpu, "contact node forces", 0)?,
                after: zeroed::<Real>(gpu, "contact nodes' state", 0)?,
                capacity: 0,
            },
            mass: storage(gpu, "masses", setup.mass)?,
            weight: storage(gpu, "weights", &weight)?,
            weighed: weight.iter().any(|&w| w != 0.0),
            claims: storage(gpu, "claims", setup.claims.as_flattened())?,
            drives: zeroed::<Real>(gpu, "drive targets", 4 * setup.drives)?,
            num_drives: setup.drives,
            scalars: zeroed::<Real>(gpu, "update scalars", 2)?,
            terms: zeroed::<Real>(gpu, "power terms", 3 * nodes)?,
            partial: zeroed::<Real>(gpu, "chunk sums", chunks)?,
            totals: zeroed::<Real>(gpu, "sums", slots)?,
            listed: storage(gpu, "listed nodes", setup.listed)?,
            num_listed: setup.listed.len(),
            compacted: zeroed::<Real>(gpu, "listed nodes' state", 12 * setup.listed.len())?,
            watched: zeroed::<u32>(gpu, "watched nodes", 0)?,
            num_watched: 0,
            watched_out: zeroed::<Real>(gpu, "watched nodes' state", 0)?,
            shapes,
            surfaces,
            load_shapes,
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

    /// Adds contact forces to the update: each node's force of the host's
    /// contact pass, set by [`Bulk::advance`]'s `contact` (zero until
    /// then).
    pub fn enable_contact_forces(&mut self) -> Result<(), GpuError> {
        let f = zeroed::<Real>(&self.gpu, "contact forces", 3 * self.num_nodes)?;
        self.motion.as_mut().expect("Bulk::enable_motion first").f_contact = Some(f);
        Ok(())
    }

    /// Makes the buffers of the contact nodes hold at least `n` nodes
    /// (grown to a power of two, so that a growing contact set remakes
    /// them seldom).
    fn hold_contact_nodes(&mut self, n: usize) {
        let gpu = &self.gpu;
        let m = self.motion.as_mut().expect("Bulk::enable_motion first");
        if m.contact.capacity >= n {
            return;
        }
        // (Their dispatches keep no bind group: nothing to forget.)
        let capacity = n.next_power_of_two();
        let fits = "a few bytes a node fit where all nodes' state does";
        m.contact = ContactNodes {
            nodes: zeroed::<u32>(gpu, "contact nodes", capacity).expect(fits),
            forces: zeroed::<Real>(gpu, "contact node forces", 3 * capacity).expect(fits),
            after: zeroed::<Real>(gpu, "contact nodes' state", 6 * capacity).expect(fits),
            capacity,
        };
    }

    /// Replaces the nodes whose positions and velocities the host reads
    /// every step besides the listed ones ([`Bulk::forces_resident`]): the
    /// nodes its contact pass reads.
    pub fn set_watched(&mut self, watched: &[u32]) -> Result<(), GpuError> {
        let gpu = &self.gpu;
        let m = self.motion.as_mut().expect("Bulk::enable_motion first");
        self.groups.forget(&m.watched);
        self.groups.forget(&m.watched_out);
        m.watched = storage(gpu, "watched nodes", watched)?;
        m.num_watched = watched.len();
        m.watched_out = zeroed::<Real>(gpu, "watched nodes' state", 6 * watched.len())?;
        Ok(())
    }

    /// Records the compact pass (`wgsl/compact.wgsl`) of the `n` nodes in
    /// `nodes` into `out`: their position, velocity, internal and
    /// surface-load force, or with `motion_only` their position and
    /// velocity; its bind group kept where `keep` (the list stays).
    fn encode_compact(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        nodes: &wgpu::Buffer,
        n: usize,
        out: &wgpu::Buffer,
        motion_only: bool,
        keep: bool,
    ) {
        let m = self.motion();
        // Without surface loads, any f64 array the kernel only reads.
        let surface = m.surfaces.as_ref().map_or(&self.x, |s| &s.f_surface);
        let flags = u32::from(m.surfaces.is_some()) | (u32::from(motion_only) << 1);
        dispatch(
            &self.gpu,
            keep.then_some(&self.groups),
            encoder,
            &m.compact_kernel,
            Params { count: count(n), flags, pad: [0; 2] },
            &[&self.x, &self.v, &self.internal, nodes, out, surface],
        );
    }

    /// Stage 1 ([`Bulk::forces`] with `want`), the sums `sums` of it, the
    /// surface loads at the factors `factors` (one per load: their ramps
    /// at `t_n`), the listed nodes' position, velocity, internal force
    /// and surface-load force and the watched nodes' position and
    /// velocity, in one submission and one read-back ([`Resident`]). The
    /// sums land in the totals that [`Bulk::advance`] returns.
    pub fn forces_resident(&mut self, want: Evaluate, sums: &[Sum], factors: &[Real]) -> Resident {
        let mut back = Resident::default();
        self.forces_resident_into(want, sums, factors, &mut back);
        back
    }

    /// [`Bulk::forces_resident`] into `back`, whose vectors are reused
    /// (decoded from the mapped read-back: no allocation once they have
    /// grown to the lists' lengths).
    pub fn forces_resident_into(&mut self, want: Evaluate, sums: &[Sum], factors: &[Real], back: &mut Resident) {
        let gpu = &self.gpu;
        let m = self.motion();
        let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        self.encode_forces(&mut encoder, want);
        for &sum in sums {
            let (source, items, finite) = match sum {
                Sum::TetEnergy => (&self.energy, self.num_tets, false),
                Sum::Dissipation => (&self.rate, self.num_tets, true),
                Sum::JointEnergy | Sum::Fracture => (&self.joint_sums, self.num_joints, false),
                Sum::WeightBack | Sum::WeightAhead | Sum::Kinetic => panic!("{sum:?} is taken by Bulk::advance"),
            };
            self.encode_sum(&mut encoder, source, items, &m.shapes[sum as usize], finite);
        }
        match &m.surfaces {
            Some(s) => {
                s.encode_forces(gpu, &self.groups, &mut encoder, &self.x, &self.v, factors);
                for (&(first, end), shapes) in s.ranges.iter().zip(&m.load_shapes) {
                    for shape in &shapes[..4] {
                        self.encode_sum(&mut encoder, &s.terms, end - first, shape, false);
                    }
                }
            }
            None => assert!(factors.is_empty(), "no surface loads on the device"),
        }
        self.encode_compact(&mut encoder, &m.listed, m.num_listed, &m.compacted, false, true);
        self.encode_compact(&mut encoder, &m.watched, m.num_watched, &m.watched_out, true, true);
        let failed_words = if self.num_joints > 0 { 4 } else { 0 };
        let copies = [
            (&self.failed_list, 0, failed_words),
            (&m.compacted, 0, 96 * m.num_listed as u64),
            (&m.watched_out, 0, 48 * m.num_watched as u64),
        ];
        submit_and_read_with(gpu, ReadBack::Forces, encoder, &copies, |bytes| {
            back.failed =
                if failed_words > 0 { u32::from_le_bytes(bytes[0][..4].try_into().expect("4 bytes")) } else { 0 };
            vectors_into(bytes[1], &mut back.listed);
            vectors_into(bytes[2], &mut back.watched);
        });
    }

    /// The central-difference update of step `n` over `dt` with the
    /// internal and surface-load forces of the last
    /// [`Bulk::forces_resident`] and, after
    /// [`Bulk::enable_contact_forces`], the contact forces: `contact` sets
    /// the contact force of the nodes it lists (the others keep theirs):
    /// `drives[d]` is drive `d`'s target velocity and whether it is active;
    /// `keep_before` keeps `v_{n−½}` for the next dissipation rate.
    /// Returns the step's sums and the new positions and velocities of the
    /// nodes `contact` lists ([`Totals`]).
    pub fn advance(&mut self, dt: Real, drives: &[(Vec3, bool)], keep_before: bool, contact: &[(u32, Vec3)]) -> Totals {
        if !contact.is_empty() {
            self.hold_contact_nodes(contact.len());
        }
        let gpu = &self.gpu;
        let m = self.motion();
        assert_eq!(drives.len(), m.num_drives, "one target per drive");
        let table: Vec<Real> = drives.iter().flat_map(|(t, on)| [t.x, t.y, t.z, Real::from(u8::from(*on))]).collect();
        write(gpu, &m.drives, &table);
        write(gpu, &m.scalars, &[dt, 0.0]);
        let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        // The contact forces down, and where the nodes' new state will go.
        let contact_nodes = (!contact.is_empty()).then(|| {
            let f = m.f_contact.as_ref().expect("Bulk::enable_contact_forces first");
            let c = &m.contact;
            let nodes: Vec<u32> = contact.iter().map(|c| c.0).collect();
            let values: Vec<Real> = contact.iter().flat_map(|c| [c.1.x, c.1.y, c.1.z]).collect();
            write(gpu, &c.nodes, &nodes);
            write(gpu, &c.forces, &values);
            let params = Params { count: count(contact.len()), flags: 0, pad: [0; 2] };
            // Not kept: the count changes from step to step.
            dispatch(gpu, None, &mut encoder, &m.scatter_kernel, params, &[&c.nodes, &c.forces, f]);
            (&c.nodes, &c.after)
        });
        // Without surface loads or contact, any f64 array the kernel only
        // reads.
        let surface = m.surfaces.as_ref().map_or(&m.mass, |s| &s.f_surface);
        let f_contact = m.f_contact.as_ref().unwrap_or(&m.mass);
        let flags =
            u32::from(keep_before) | (u32::from(m.surfaces.is_some()) << 1) | (u32::from(m.f_contact.is_some()) << 2);
        dispatch(
            gpu,
            Some(&self.groups),
            &mut encoder,
            &m.update_kernel,
            Params { count: count(self.num_nodes), flags, pad: [0; 2] },
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
                surface,
                f_contact,
            ],
        );
        let gravity: &[Sum] = if m.weighed { &[Sum::WeightBack, Sum::WeightAhead] } else { &[] };
        for &sum in gravity.iter().chain(&[Sum::Kinetic]) {
            self.encode_sum(&mut encoder, &m.terms, self.num_nodes, &m.shapes[sum as usize], false);
        }
        if let Some(s) = &m.surfaces {
            s.encode_ahead(gpu, &self.groups, &mut encoder, &self.x, &self.v);
            for (&(first, end), shapes) in s.ranges.iter().zip(&m.load_shapes) {
                self.encode_sum(&mut encoder, &s.terms, end - first, &shapes[4], false);
            }
        }
        // The contact nodes' new state, for the contact pass's account.
        let loads = m.surfaces.as_ref().map_or(0, Surfaces::len);
        let mut copies = vec![(&m.totals, 0, 8 * (FIXED + TERMS * loads) as u64)];
        if let Some((nodes, after)) = contact_nodes {
            // Not kept: the count changes from step to step.
            self.encode_compact(&mut encoder, nodes, contact.len(), after, true, false);
            copies.push((after, 0, 48 * contact.len() as u64));
        }
        let bytes = submit_and_read_as(gpu, ReadBack::Update, encoder, &copies);
        let t: Vec<Real> = bytemuck::pod_collect_to_vec(&bytes[0]);
        Totals {
            contact_nodes: bytes.get(1).map_or_else(Vec::new, |b| vectors(b)),
            sums: std::array::from_fn(|k| t[k]),
            loads: t[FIXED..]
                .chunks_exact(TERMS)
                .map(|c| LoadSums { force: Vec3::new(c[0], c[1], c[2]) * 3.0, back: c[3], ahead: c[4] })
                .collect(),
        }
    }

    /// The kinetic-energy sum over the nodes alone, recorded into
    /// `encoder` (what [`Bulk::timings`] times; `None` before
    /// [`Bulk::enable_motion`]).
    pub(crate) fn encode_kinetic_sum(&self, encoder: &mut wgpu::CommandEncoder) -> Option<()> {
        let m = self.motion.as_ref()?;
        self.encode_sum(encoder, &m.terms, self.num_nodes, &m.shapes[Sum::Kinetic as usize], false);
        Some(())
    }

    /// A two-pass sum of `input[stride k + offset]`, `k < items`, into the
    /// totals slot, stride and offset of `shape` (`wgsl/reduce.wgsl`),
    /// recorded into `encoder`.
    fn encode_sum(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        input: &wgpu::Buffer,
        items: usize,
        shape: &wgpu::Buffer,
        finite: bool,
    ) {
        let gpu = &self.gpu;
        let m = self.motion();
        let buffers = [input, &m.partial, &m.totals, shape];
        // One workgroup of 64 per chunk, then one for the chunks' sums.
        let chunks = items.div_ceil(CHUNK);
        let pass = |groups: usize, flags| Params { count: count(64 * groups), flags, pad: [count(items), 0] };
        let groups = Some(&self.groups);
        dispatch(gpu, groups, encoder, &m.reduce_kernel, pass(chunks, u32::from(finite)), &buffers);
        dispatch(gpu, groups, encoder, &m.reduce_kernel, pass(1, 2), &buffers);
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

/// Groups of `N` vectors from read-back bytes.
fn vectors<const N: usize>(bytes: &[u8]) -> Vec<[Vec3; N]> {
    let mut out = Vec::new();
    vectors_into(bytes, &mut out);
    out
}

/// Groups of `N` vectors from read-back bytes into `out` (emptied first,
/// its memory reused).
fn vectors_into<const N: usize>(bytes: &[u8], out: &mut Vec<[Vec3; N]>) {
    out.clear();
    out.extend(
        reals(bytes)
            .chunks_exact(3 * N)
            .map(|c| std::array::from_fn(|k| Vec3::new(c[3 * k], c[3 * k + 1], c[3 * k + 2]))),
    );
}

fn unflat(f: &[Real]) -> Vec<Vec3> {
    f.chunks_exact(3).map(|c| Vec3::new(c[0], c[1], c[2])).collect()
}
