//! Internal forces: the tet pass (Eq. 1–2), the joint pass (Eq. 11), and a
//! gather that sums each node's slots in a fixed order.
//!
//! Both passes run in parallel over fixed-size chunks and write only their
//! own element's force slots; the gather then runs in parallel over nodes,
//! each summing its slots in increasing slot order. No floating-point sum
//! depends on the thread count, so results are identical bit for bit with
//! one thread or many. Energy sums are taken per chunk and then added in
//! chunk order, for the same reason.

use femdem_core::{Mat3, Real, Vec3};
use femdem_fracture::{FailureMode, JointHistory, KernelConsts, LANES, joint_update_fast, joint_update_lanes};
use femdem_material::{
    Material, TET_LANES, TetReference, deformation_gradient, tet_forces, tet_forces_lanes, velocity_gradient,
};
use rayon::prelude::*;

use crate::model::Model;
use crate::widest::{Pass, VectorPath, widest};

/// Elements per parallel work item.
pub const CHUNK: usize = 512;

/// What a force evaluation should compute besides the forces.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Want {
    /// Store each tet's Cauchy stress.
    pub stress: bool,
    /// Sum the stored elastic energies.
    pub energy: bool,
}

/// Sums returned by [`internal_forces`] (zero where not asked for).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ForceSums {
    /// Elastic energy stored in the tets, J.
    pub tet_energy: Real,
    /// Elastic energy stored in the joints, J.
    pub joint_energy: Real,
    /// Rate of viscous dissipation in the tets, W.
    pub dissipation_rate: Real,
    /// Energy the joints have dissipated (fracture): the work done on them
    /// less the energy the intact ones store, J.
    pub fracture: Real,
    /// Joints that failed in this evaluation.
    pub newly_failed: usize,
}

impl ForceSums {
    fn add(self, o: ForceSums) -> ForceSums {
        ForceSums {
            tet_energy: self.tet_energy + o.tet_energy,
            joint_energy: self.joint_energy + o.joint_energy,
            dissipation_rate: self.dissipation_rate + o.dissipation_rate,
            fracture: self.fracture + o.fracture,
            newly_failed: self.newly_failed + o.newly_failed,
        }
    }
}

/// Whether [`internal_forces`] sums the viscous dissipation rate, and
/// against which velocities.
///
/// The viscous (Kelvin–Voigt) forces of Eq. 1 at step `n` are
/// `f_v,n = −C_n v_{n−½}`, `C_n` the damping operator on `x_n`
/// (`σ_v = η D`). Over the interval `[t_{n−1}, t_n]` they do the
/// trapezoidal work of the energy account (`crate::step`),
/// `½ Δt (f_v,n−1 + f_v,n) · v_{n−½}`; taking `C_{n−1} = C_n` (the
/// geometry moves by one step: a second-order change), the energy they
/// dissipate over it is `Δt` times
///
/// ```text
/// R_n = v_{n−½}ᵀ C_n v̄,   v̄ = ½ (v_{n−3/2} + v_{n−½}):   R_n = ∫ η D(v_{n−½}) : D(v̄) dv
/// ```
///
/// The rate `∫ η D:D dv` of `v_{n−½}` alone books `¼ Δt Σ Δvᵀ C Δv` too
/// much per step (`Δv = v_{n−½} − v_{n−3/2}`): nothing while the motion is
/// smooth, but steadily where failures shake the mesh (measured: 0.35% of
/// the work of the bundled Brazilian run, 0.46% of the pulled bar).
#[derive(Clone, Copy, Debug)]
pub enum Dissipation<'a> {
    /// Not summed (0).
    None,
    /// `R_n` above, given the velocities of the step before, `v_{n−3/2}`
    /// (node by node, as `v`).
    Since(&'a [Vec3]),
}

/// Preallocated buffers of the force evaluation: no allocation per step.
#[derive(Clone, Debug)]
pub struct Workspace {
    /// Forces of each tet on its four nodes.
    pub tet_slots: Vec<[Vec3; 4]>,
    /// Forces of each joint on its six nodes.
    pub joint_slots: Vec<[Vec3; 6]>,
    /// Gathered internal force per node.
    pub internal: Vec<Vec3>,
    /// Cauchy stress per tet (filled when asked for).
    pub stress: Vec<Mat3>,
    /// How each joint that failed in the last evaluation failed (`None`
    /// for the others).
    pub failed_now: Vec<Option<FailureMode>>,
    /// Which compilation of the tet and joint passes runs
    /// ([`VectorPath::Widest`] unless a test compares the two).
    pub path: VectorPath,
    tet_partials: Vec<ForceSums>,
    joint_partials: Vec<ForceSums>,
}

impl Workspace {
    /// Buffers sized for `model`.
    pub fn new(model: &Model) -> Workspace {
        Workspace {
            tet_slots: vec![[Vec3::zeros(); 4]; model.tets.len()],
            joint_slots: vec![[Vec3::zeros(); 6]; model.joints.len()],
            internal: vec![Vec3::zeros(); model.num_nodes()],
            stress: vec![Mat3::zeros(); model.tets.len()],
            failed_now: vec![None; model.joints.len()],
            path: VectorPath::Widest,
            tet_partials: vec![ForceSums::default(); model.tets.len().div_ceil(CHUNK)],
            joint_partials: vec![ForceSums::default(); model.joints.len().div_ceil(CHUNK)],
        }
    }
}

/// Computes the internal force on every node at positions `x` and
/// velocities `v` (the velocities enter only the viscous term of Eq. 1)
/// into `ws.internal`, updates the joints' damage `history`, and returns
/// the sums asked for in `want` (the count of newly failed joints always;
/// `ws.failed_now` says which), and with `dissipation` the viscous
/// dissipation rate (see [`Dissipation`]).
pub fn internal_forces(
    model: &Model,
    x: &[Vec3],
    v: &[Vec3],
    history: &mut [JointHistory],
    ws: &mut Workspace,
    want: Want,
    dissipation: Dissipation<'_>,
) -> ForceSums {
    tet_pass(model, x, v, ws, want, dissipation);
    joint_pass(model, x, history, ws, want);
    gather(model, ws);
    let tets = ws.tet_partials.iter().fold(ForceSums::default(), |a, &b| a.add(b));
    ws.joint_partials.iter().fold(tets, |a, &b| a.add(b))
}

fn tet_pass(model: &Model, x: &[Vec3], v: &[Vec3], ws: &mut Workspace, want: Want, dissipation: Dissipation<'_>) {
    let path = ws.path;
    let stress_out = &mut ws.stress;
    ws.tet_slots
        .par_chunks_mut(CHUNK)
        .zip(stress_out.par_chunks_mut(CHUNK))
        .zip(ws.tet_partials.par_iter_mut())
        .enumerate()
        .for_each(|(c, ((slots, stresses), partial))| {
            let first = c * CHUNK;
            *partial = tet_chunk(TetChunk { model, x, v, first, slots, stresses, want, dissipation }, path);
        });
}

/// The tets `first..first + slots.len()` (one chunk of the tet pass; not
/// inlined, so that profiles name it): four at a time in SIMD lanes where
/// all four are neo-Hookean and the step asks for no stress or energy
/// ([`tet_forces_lanes`]), the others one by one ([`tet_forces`]); both
/// give the same forces bit for bit. Compiled for the widest vector unit on
/// `path` ([`widest`]).
#[inline(never)]
fn tet_chunk(chunk: TetChunk<'_>, path: VectorPath) -> ForceSums {
    widest(path, chunk)
}

/// One chunk of the tet pass: the tets `first..first + slots.len()`.
struct TetChunk<'a> {
    model: &'a Model,
    x: &'a [Vec3],
    v: &'a [Vec3],
    first: usize,
    slots: &'a mut [[Vec3; 4]],
    stresses: &'a mut [Mat3],
    want: Want,
    dissipation: Dissipation<'a>,
}

impl Pass for TetChunk<'_> {
    type Output = ForceSums;

    /// [`tet_chunk`]'s work, inlined into each compilation of it.
    #[inline(always)]
    fn run(self) -> ForceSums {
        let TetChunk { model, x, v, first, slots, stresses, want, dissipation } = self;
        let mut sums = ForceSums::default();
        let (mut xp, mut vp) = ([[Vec3::zeros(); 4]; TET_LANES], [[Vec3::zeros(); 4]; TET_LANES]);
        let groups = slots.chunks_mut(TET_LANES).zip(stresses.chunks_mut(TET_LANES));
        for (g, (slots, stresses)) in groups.enumerate() {
            let t0 = first + g * TET_LANES;
            if !want.stress && !want.energy && slots.len() == TET_LANES {
                let group_slots = <&mut [[Vec3; 4]; TET_LANES]>::try_from(&mut *slots).expect("a full group");
                let mat = |l: usize| model.tet_material[t0 + l].index().map(|m| &model.materials[m]);
                if let (Some((l0, a0)), Some((l1, a1)), Some((l2, a2)), Some((l3, a3))) =
                    (mat(0), mat(1), mat(2), mat(3))
                {
                    // The group's nodes, gathered in place (arrays built by
                    // `from_fn` or `map` may be moved with `memmove` calls,
                    // as in the joint pass).
                    for (l, (row_x, row_v)) in xp.iter_mut().zip(vp.iter_mut()).enumerate() {
                        for (k, &n) in model.tets[t0 + l].iter().enumerate() {
                            row_x[k] = x[n as usize];
                            row_v[k] = v[n as usize];
                        }
                    }
                    let r = |l: usize| &model.tet_ref[t0 + l];
                    let (laws, materials) = ([*l0, *l1, *l2, *l3], [a0, a1, a2, a3]);
                    if tet_forces_lanes(laws, materials, [r(0), r(1), r(2), r(3)], &xp, &vp, group_slots) {
                        for (l, material) in materials.into_iter().enumerate() {
                            let t = t0 + l;
                            viscous_dissipation(
                                &mut sums,
                                dissipation,
                                material,
                                r(l),
                                model.tets[t],
                                &xp[l],
                                &vp[l],
                                v,
                            );
                        }
                        continue;
                    }
                }
            }
            for (k, (slot, stress_slot)) in slots.iter_mut().zip(stresses.iter_mut()).enumerate() {
                let t = t0 + k;
                let Some(mat) = model.tet_material[t].index() else {
                    *slot = [Vec3::zeros(); 4];
                    continue;
                };
                let (law, material) = &model.materials[mat];
                let tet = model.tets[t];
                let xp = tet.map(|n| x[n as usize]);
                let vp = tet.map(|n| v[n as usize]);
                let reference = &model.tet_ref[t];
                let out = tet_forces(*law, material, reference, &xp, &vp);
                *slot = out.forces;
                if want.stress {
                    *stress_slot = out.stress;
                }
                if want.energy {
                    sums.tet_energy += out.energy;
                }
                viscous_dissipation(&mut sums, dissipation, material, reference, tet, &xp, &vp, v);
            }
        }
        sums
    }
}

/// Adds the viscous dissipation rate of one tet to `sums` where asked for
/// and the material is viscous: `R_n = ∫ η D(v_{n−½}) : D(v̄) dv`
/// ([`Dissipation`]).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn viscous_dissipation(
    sums: &mut ForceSums,
    dissipation: Dissipation<'_>,
    material: &Material,
    reference: &TetReference,
    tet: [u32; 4],
    xp: &[Vec3; 4],
    vp: &[Vec3; 4],
    v: &[Vec3],
) {
    if let (Dissipation::Since(before), true) = (dissipation, material.viscosity() > 0.0) {
        let l = velocity_gradient(xp, vp);
        let d = (l + l.transpose()) * 0.5;
        let mean = tet.map(|n| (v[n as usize] + before[n as usize]) * 0.5);
        let l_mean = velocity_gradient(xp, &mean);
        let d_mean = (l_mean + l_mean.transpose()) * 0.5;
        let j = deformation_gradient(reference, xp).determinant();
        let rate = material.viscosity() * d.dot(&d_mean) * reference.volume * j;
        if rate.is_finite() {
            sums.dissipation_rate += rate;
        }
    }
}

fn joint_pass(model: &Model, x: &[Vec3], history: &mut [JointHistory], ws: &mut Workspace, want: Want) {
    let path = ws.path;
    ws.joint_slots
        .par_chunks_mut(CHUNK)
        .zip(history.par_chunks_mut(CHUNK))
        .zip(ws.failed_now.par_chunks_mut(CHUNK))
        .zip(ws.joint_partials.par_iter_mut())
        .enumerate()
        .for_each(|(c, (((slots, hist), failed), partial))| {
            let first = c * CHUNK;
            *partial = joint_chunk(JointChunk { model, x, first, slots, hist, failed, want }, path);
        });
}

/// The joints `first..first + slots.len()` (one chunk of the joint pass;
/// not inlined, so that profiles name it): four at a time in SIMD lanes
/// where all four are intact and stay elastic ([`joint_update_lanes`]),
/// the others one by one ([`joint_update_fast`]); both give the law's
/// results bit for bit, so which one runs changes nothing. A step that asks
/// for energies runs the scalar kernel throughout (the lanes compute none).
/// Compiled for the widest vector unit on `path` ([`widest`]).
#[inline(never)]
fn joint_chunk(chunk: JointChunk<'_>, path: VectorPath) -> ForceSums {
    widest(path, chunk)
}

/// One chunk of the joint pass: the joints `first..first + slots.len()`.
struct JointChunk<'a> {
    model: &'a Model,
    x: &'a [Vec3],
    first: usize,
    slots: &'a mut [[Vec3; 6]],
    hist: &'a mut [JointHistory],
    failed: &'a mut [Option<FailureMode>],
    want: Want,
}

impl Pass for JointChunk<'_> {
    type Output = ForceSums;

    /// [`joint_chunk`]'s work, inlined into each compilation of it.
    #[inline(always)]
    fn run(self) -> ForceSums {
        let JointChunk { model, x, first, slots, hist, failed, want } = self;
        let consts = KernelConsts::new();
        let mut sums = ForceSums::default();
        // The group's node positions, gathered in place: built by `from_fn`
        // and `map`, the arrays were moved with a `memmove` call each, 7% of
        // the 1.2 mm disc's step (perf, 2026-11-25).
        let mut xp = [[Vec3::zeros(); 6]; LANES];
        let groups = slots.chunks_mut(LANES).zip(hist.chunks_mut(LANES)).zip(failed.chunks_mut(LANES));
        for (g, ((slots, hist), failed)) in groups.enumerate() {
            let j0 = first + g * LANES;
            if !want.energy && slots.len() == LANES {
                let (group_slots, group_hist) = (
                    <&mut [[Vec3; 6]; LANES]>::try_from(&mut *slots).expect("a full group"),
                    <&mut [JointHistory; LANES]>::try_from(&mut *hist).expect("a full group"),
                );
                let law = |l: usize| &model.joint_law[j0 + l];
                for (l, row) in xp.iter_mut().enumerate() {
                    for (p, &n) in row.iter_mut().zip(&model.joints[j0 + l]) {
                        *p = x[n as usize];
                    }
                }
                if joint_update_lanes(&consts, [law(0), law(1), law(2), law(3)], group_hist, &xp, group_slots) {
                    failed.fill(None);
                    continue;
                }
            }
            for (k, ((slot, h), f)) in slots.iter_mut().zip(hist.iter_mut()).zip(failed.iter_mut()).enumerate() {
                let j = j0 + k;
                *f = None;
                if h.failed {
                    // Left the force loop when it failed (naturally, or by
                    // `Solver::break_joints`): no force, all its work lost.
                    *slot = [Vec3::zeros(); 6];
                    if want.energy {
                        sums.fracture += h.work;
                    }
                    continue;
                }
                let xp = model.joints[j].map(|n| x[n as usize]);
                let out = joint_update_fast(&consts, &model.joint_law[j], h, &xp, want.energy);
                *slot = out.forces;
                if out.failed.is_some() {
                    *f = out.failed;
                    sums.newly_failed += 1;
                }
                if want.energy {
                    sums.joint_energy += out.energy;
                    sums.fracture += if h.failed { h.work } else { h.work - out.energy };
                }
            }
        }
        sums
    }
}

fn gather(model: &Model, ws: &mut Workspace) {
    // Slot `s` of a gather table is `element * nodes_per_element + local`:
    // its index in the flattened slots, with no division.
    let tet_slots = ws.tet_slots.as_flattened();
    let joint_slots = ws.joint_slots.as_flattened();
    ws.internal
        .par_chunks_mut(CHUNK)
        .enumerate()
        .for_each(|(c, out)| gather_chunk(model, tet_slots, joint_slots, c * CHUNK, out));
}

/// The nodes `first..first + out.len()` (one chunk of the gather; not
/// inlined, so that profiles name it): each node's tet slots, then its
/// joint slots, in increasing slot order.
#[inline(never)]
fn gather_chunk(model: &Model, tet_slots: &[Vec3], joint_slots: &[Vec3], first: usize, out: &mut [Vec3]) {
    let (tg, jg) = (&model.tet_gather, &model.joint_gather);
    let tet_rows = tg.offsets[first..=first + out.len()].windows(2);
    let joint_rows = jg.offsets[first..=first + out.len()].windows(2);
    for ((f, t), j) in out.iter_mut().zip(tet_rows).zip(joint_rows) {
        let mut sum = Vec3::zeros();
        for &s in &tg.slots[t[0] as usize..t[1] as usize] {
            sum += tet_slots[s as usize];
        }
        for &s in &jg.slots[j[0] as usize..j[1] as usize] {
            sum += joint_slots[s as usize];
        }
        *f = sum;
    }
}
