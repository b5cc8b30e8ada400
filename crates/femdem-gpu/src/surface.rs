//! Surface loads on the device (`wgsl/surface.wgsl`): pressures and
//! tractions on the current geometry, `femdem_solver::loads::surface_forces`
//! on the device, so that a scene with them keeps its positions and
//! velocities there.
//!
//! Each face's nodal share, `A t s / 3` with `t = −p n` (pressure) or the
//! traction, is computed once per step; each loaded node adds the shares
//! of its faces from zero in (load, face) order, the CPU's order, so its
//! force is the CPU's to the faces' round-off. Each load's total force and
//! its powers against `v_{n−½}` and `v_{n+½}` are summed over its faces in
//! the CPU's chunk order (the CPU sums them node by node in one sequence:
//! the two agree to round-off).

use femdem_core::{Real, Vec3};

use crate::buffers::{Groups, Params, dispatch, storage, write, zeroed};
use crate::device::{Gpu, GpuError};
use crate::kernels;

/// What a surface load applies on each face.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SurfaceKind {
    /// Pressure, Pa, along the inward normal of the current face.
    Pressure(Real),
    /// Traction, Pa, a fixed vector per unit current area.
    Traction(Vec3),
}

/// A pressure or traction on a set of boundary faces.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceLoad<'a> {
    /// Face node triples, counter-clockwise seen from outside the body.
    pub faces: &'a [[u32; 3]],
    /// Pressure or traction.
    pub kind: SurfaceKind,
}

/// One surface load's sums over a step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LoadSums {
    /// Its total force at `t_n`, N.
    pub force: Vec3,
    /// Its power against `v_{n−½}`, `Σ f_n · v_{n−½}`, W.
    pub back: Real,
    /// Its power against `v_{n+½}`, W.
    pub ahead: Real,
}

/// Numbers per face in the terms buffer: share (3), back, ahead.
pub(crate) const TERMS: usize = 5;

/// The surface loads' buffers.
#[derive(Debug)]
pub(crate) struct Surfaces {
    kernel: wgpu::ComputePipeline,
    faces: wgpu::Buffer,
    face_load: wgpu::Buffer,
    table: wgpu::Buffer,
    pub(crate) terms: wgpu::Buffer,
    loaded: wgpu::Buffer,
    offsets: wgpu::Buffer,
    entries: wgpu::Buffer,
    /// Each node's surface-load force, N (zero off the loaded nodes).
    pub(crate) f_surface: wgpu::Buffer,
    num_faces: usize,
    num_loaded: usize,
    kinds: Vec<SurfaceKind>,
    /// Each load's faces, `first..end` in the face arrays.
    pub(crate) ranges: Vec<(usize, usize)>,
}

fn count(n: usize) -> u32 {
    u32::try_from(n).expect("at most 2^32 items per kernel")
}

impl Surfaces {
    /// `None` without loads.
    pub(crate) fn new(gpu: &Gpu, loads: &[SurfaceLoad<'_>], nodes: usize) -> Result<Option<Surfaces>, GpuError> {
        if loads.is_empty() {
            return Ok(None);
        }
        let faces: Vec<[u32; 3]> = loads.iter().flat_map(|l| l.faces.iter().copied()).collect();
        let face_load: Vec<u32> =
            loads.iter().enumerate().flat_map(|(k, l)| std::iter::repeat_n(count(k), l.faces.len())).collect();
        let ranges = loads
            .iter()
            .scan(0, |at, l| {
                let first = *at;
                *at += l.faces.len();
                Some((first, *at))
            })
            .collect();
        // Each loaded node's faces, in face order (compressed rows).
        let mut rows: Vec<Vec<u32>> = vec![Vec::new(); nodes];
        for (j, f) in faces.iter().enumerate() {
            for &n in f {
                rows[n as usize].push(count(j));
            }
        }
        let loaded: Vec<u32> = (0..nodes).filter(|&n| !rows[n].is_empty()).map(count).collect();
        let mut offsets = vec![0u32];
        let mut entries = Vec::new();
        for &n in &loaded {
            entries.extend_from_slice(&rows[n as usize]);
            offsets.push(count(entries.len()));
        }
        let module = gpu.module("surface", &kernels::surface())?;
        Ok(Some(Surfaces {
            kernel: gpu.pipeline("surface", &module)?,
            faces: storage(gpu, "loaded faces", faces.as_flattened())?,
            face_load: storage(gpu, "loaded faces' loads", &face_load)?,
            table: zeroed::<Real>(gpu, "surface loads", 6 * loads.len())?,
            terms: zeroed::<Real>(gpu, "loaded faces' terms", TERMS * faces.len())?,
            loaded: storage(gpu, "loaded nodes", &loaded)?,
            offsets: storage(gpu, "loaded nodes' offsets", &offsets)?,
            entries: storage(gpu, "loaded nodes' faces", &entries)?,
            f_surface: zeroed::<Real>(gpu, "surface forces", 3 * nodes)?,
            num_faces: faces.len(),
            num_loaded: loaded.len(),
            kinds: loads.iter().map(|l| l.kind).collect(),
            ranges,
        }))
    }

    fn pass(
        &self,
        gpu: &Gpu,
        groups: &Groups,
        encoder: &mut wgpu::CommandEncoder,
        pass: u32,
        x: &wgpu::Buffer,
        v: &wgpu::Buffer,
    ) {
        let items = if pass == 1 { self.num_loaded } else { self.num_faces };
        dispatch(
            gpu,
            Some(groups),
            encoder,
            &self.kernel,
            Params { count: count(items), flags: pass, pad: [0; 2] },
            &[
                x,
                v,
                &self.faces,
                &self.face_load,
                &self.table,
                &self.terms,
                &self.loaded,
                &self.offsets,
                &self.entries,
                &self.f_surface,
            ],
        );
    }

    /// Records the faces' shares and powers against the velocities in `v`
    /// (`v_{n−½}`) at the loads' factors `factors` (one per load, the
    /// ramps at `t_n`), and each loaded node's force.
    pub(crate) fn encode_forces(
        &self,
        gpu: &Gpu,
        groups: &Groups,
        encoder: &mut wgpu::CommandEncoder,
        x: &wgpu::Buffer,
        v: &wgpu::Buffer,
        factors: &[Real],
    ) {
        assert_eq!(factors.len(), self.kinds.len(), "one factor per surface load");
        let table: Vec<Real> = self
            .kinds
            .iter()
            .zip(factors)
            .flat_map(|(kind, &s)| match *kind {
                SurfaceKind::Pressure(p) => [0.0, s, p, 0.0, 0.0, 0.0],
                SurfaceKind::Traction(t) => [1.0, s, 0.0, t.x, t.y, t.z],
            })
            .collect();
        write(gpu, &self.table, &table);
        self.pass(gpu, groups, encoder, 0, x, v);
        self.pass(gpu, groups, encoder, 1, x, v);
    }

    /// Records the faces' powers against the velocities in `v` (`v_{n+½}`,
    /// after the update).
    pub(crate) fn encode_ahead(
        &self,
        gpu: &Gpu,
        groups: &Groups,
        encoder: &mut wgpu::CommandEncoder,
        x: &wgpu::Buffer,
        v: &wgpu::Buffer,
    ) {
        self.pass(gpu, groups, encoder, 2, x, v);
    }

    /// How many loads there are.
    pub(crate) fn len(&self) -> usize {
        self.kinds.len()
    }
}
