//! The potential contact force of Eq. 17 between pairs of tets on the
//! device (`wgsl/pairs.wgsl`), one pair per invocation: the reference
//! clipping `femdem_contact::tet_tet_contact` ([`pair_contacts`]), and
//! what the solver's contact pass calls with its `negligible` threshold,
//! `femdem_contact::tet_tet_contact_within` ([`pair_contacts_within`]:
//! the pair's bound, `wgsl/pair_bound.wgsl`, and faces left out). The
//! bricks of contact on the device (issue 35); what the pass adds —
//! friction, the start-at-zero activation, the certified pairs, the sum
//! into nodal forces — is not here yet.

use std::time::Instant;

use femdem_core::{Real, Vec3};
use rayon::prelude::*;

use crate::buffers::{Params, dispatch, read, reals, storage, submit_and_read_with, write, zeroed};
use crate::device::{Gpu, GpuError};
use crate::kernels;
use crate::transfers::{Part, ReadBack};

/// Numbers the kernel writes per pair: forces on `a`'s and `b`'s nodes,
/// `Σ |F_k| P_k`, `Σ |F_k|`, the pair's bound and whether it is
/// negligible.
const OUT: usize = 30;

/// The contact of one pair of tets, as `femdem_contact::TetTetContact`
/// has it, with the weight of its centre.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairContact {
    /// Forces on `a`'s four nodes, N.
    pub on_a: [Vec3; 4],
    /// Forces on `b`'s four nodes, N.
    pub on_b: [Vec3; 4],
    /// The contact centre `Σ |F_k| P_k / Σ |F_k|` over the clipped pieces;
    /// `None` when no piece carries a force.
    pub centre: Option<Vec3>,
    /// `Σ |F_k|`, N.
    pub weight: Real,
}

/// What the device found of one pair with a threshold
/// ([`pair_contacts_within`]), as `femdem_contact::Bounded` has it (and,
/// like it, unboxed: results come in arrays).
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PairBounded {
    /// The pair's bound (`femdem_contact::contact_bound`, m²), at most the
    /// threshold: nothing was clipped.
    Negligible(Real),
    /// The pair's contact with faces left out up to the threshold.
    Contact(PairContact),
}

/// The contacts of `pairs` (indices into `tets`, whose nodes index `x`)
/// at penalty `penalty` (Pa), computed on the device in one dispatch:
/// `femdem_contact::tet_tet_contact` pair by pair.
///
/// # Errors
/// The kernel refused by the adapter, or arrays larger than one of its
/// storage bindings.
pub fn pair_contacts(
    gpu: &Gpu,
    x: &[Vec3],
    tets: &[[u32; 4]],
    pairs: &[[u32; 2]],
    penalty: Real,
) -> Result<Vec<PairContact>, GpuError> {
    let out = run(gpu, x, tets, pairs, None, penalty)?;
    Ok(out.chunks_exact(OUT).map(contact_of).collect())
}

/// [`pair_contacts`] with a threshold `omits[k]` (m²) for pair `k`:
/// `femdem_contact::tet_tet_contact_within(a, b, penalty, omits[k], _)`
/// pair by pair (the pair's bound first; negligible where it is at most
/// the threshold; else faces left out while their bounds fit in it).
///
/// # Errors
/// As [`pair_contacts`].
pub fn pair_contacts_within(
    gpu: &Gpu,
    x: &[Vec3],
    tets: &[[u32; 4]],
    pairs: &[[u32; 2]],
    omits: &[Real],
    penalty: Real,
) -> Result<Vec<PairBounded>, GpuError> {
    assert_eq!(omits.len(), pairs.len(), "one threshold per pair");
    let out = run(gpu, x, tets, pairs, Some(omits), penalty)?;
    Ok(out.chunks_exact(OUT).map(|c| bounded_of(c, true)).collect())
}

/// The kernel's numbers of every pair, with thresholds where given.
fn run(
    gpu: &Gpu,
    x: &[Vec3],
    tets: &[[u32; 4]],
    pairs: &[[u32; 2]],
    omits: Option<&[Real]>,
    penalty: Real,
) -> Result<Vec<Real>, GpuError> {
    let module = gpu.module("pairs", &kernels::pairs())?;
    let pipeline = gpu.pipeline("pairs", &module)?;
    let flat: Vec<Real> = x.iter().flat_map(|p| [p.x, p.y, p.z]).collect();
    let xb = storage(gpu, "contact positions", &flat)?;
    let tb = storage(gpu, "contact tets", tets.as_flattened())?;
    let pb = storage(gpu, "contact pairs", pairs.as_flattened())?;
    let sb = storage(gpu, "contact penalty", &[penalty])?;
    let ob = zeroed::<Real>(gpu, "pair contacts", OUT * pairs.len())?;
    let mb = storage(gpu, "contact thresholds", omits.unwrap_or(&[]))?;
    let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    let count = u32::try_from(pairs.len()).expect("at most 2^32 pairs");
    let params = Params { count, flags: u32::from(omits.is_some()), pad: [0; 2] };
    dispatch(gpu, None, &mut encoder, &pipeline, params, &[&xb, &tb, &pb, &sb, &ob, &mb]);
    gpu.queue.submit([encoder.finish()]);
    Ok(read(gpu, &ob, OUT * pairs.len()))
}

/// A pair's contact from its numbers.
fn contact_of(c: &[Real]) -> PairContact {
    let v = |k: usize| Vec3::new(c[3 * k], c[3 * k + 1], c[3 * k + 2]);
    let (moment, weight) = (v(8), c[27]);
    PairContact {
        on_a: std::array::from_fn(v),
        on_b: std::array::from_fn(|k| v(4 + k)),
        centre: (weight > 0.0).then(|| moment / weight),
        weight,
    }
}

/// The pairs [`Bulk::pair_geometry`] evaluates and where their results go,
/// kept between calls (grown to a power of two, up to what one binding
/// holds).
#[derive(Debug)]
pub(crate) struct PairBuffers {
    pairs: wgpu::Buffer,
    omits: wgpu::Buffer,
    out: wgpu::Buffer,
    penalty: wgpu::Buffer,
    capacity: usize,
    /// The last call's pairs and whether it had thresholds (what
    /// [`crate::Bulk::timings`] dispatches again).
    pub(crate) last: (u32, bool),
}

/// The pair kernel of a [`crate::Bulk`]: compiled once, or the reason the
/// adapter refused it (then every call is refused at once).
#[derive(Debug)]
pub(crate) enum PairKernel {
    Ready(wgpu::ComputePipeline),
    Refused(String),
}

impl crate::Bulk {
    /// The Eq. 17 contacts of `pairs` (tet indices) at the device's
    /// current positions, penalty `penalty` (Pa): with `omits` (m², one per
    /// pair) as [`pair_contacts_within`], without as [`pair_contacts`]
    /// (wrapped in [`PairBounded::Contact`]). One upload of the pairs, one
    /// dispatch and one read-back of 240 bytes a pair.
    ///
    /// # Errors
    /// The kernel refused by the adapter (once compiled or refused, the
    /// answer is kept), or more pairs than one storage binding holds.
    pub fn pair_geometry(
        &mut self,
        pairs: &[[u32; 2]],
        omits: Option<&[Real]>,
        penalty: Real,
    ) -> Result<Vec<PairBounded>, GpuError> {
        let mut found = Vec::new();
        self.pair_geometry_into(pairs, omits, penalty, &mut found, |p| p)?;
        Ok(found)
    }

    /// [`Bulk::pair_geometry`] into `out` (emptied first, its memory
    /// reused), each pair's result turned into a `T` by `convert`: decoded
    /// from the mapped read-back on all threads, in the pairs' order, with
    /// no copy of the results made first (at the paper's multi-layer size
    /// some 10⁵ pairs a step, whose fresh vectors cost more than the
    /// device's copy: `docs/performance.md`).
    ///
    /// # Errors
    /// As [`Bulk::pair_geometry`]; `out` is left empty then.
    pub fn pair_geometry_into<T: Send>(
        &mut self,
        pairs: &[[u32; 2]],
        omits: Option<&[Real]>,
        penalty: Real,
        out: &mut Vec<T>,
        convert: impl Fn(PairBounded) -> T + Sync + Send,
    ) -> Result<(), GpuError> {
        out.clear();
        if pairs.is_empty() {
            return Ok(());
        }
        if let Some(o) = omits {
            assert_eq!(o.len(), pairs.len(), "one threshold per pair");
        }
        let gpu = self.gpu.clone();
        self.prepare_pair_kernel();
        let pipeline = match self.pair_kernel.as_ref().expect("set above") {
            PairKernel::Ready(p) => p.clone(),
            PairKernel::Refused(reason) => {
                return Err(GpuError::Kernel { kernel: "pairs", adapter: gpu.adapter(), reason: reason.clone() });
            }
        };
        if self.pair_buffers.as_ref().is_none_or(|b| b.capacity < pairs.len()) {
            // A power of two where one binding holds it, else just enough.
            let most = usize::try_from(gpu.max_binding() / (8 * OUT as u64)).unwrap_or(usize::MAX);
            let capacity = pairs.len().next_power_of_two().min(most).max(pairs.len());
            self.pair_buffers = None;
            self.pair_buffers = Some(PairBuffers {
                pairs: zeroed::<u32>(&gpu, "contact pairs", 2 * capacity)?,
                omits: zeroed::<Real>(&gpu, "contact thresholds", capacity)?,
                out: zeroed::<Real>(&gpu, "pair contacts", OUT * capacity)?,
                penalty: zeroed::<Real>(&gpu, "contact penalty", 1)?,
                capacity,
                last: (0, false),
            });
        }
        let start = Instant::now();
        let b = self.pair_buffers.as_ref().expect("made above");
        write(&gpu, &b.pairs, pairs.as_flattened());
        write(&gpu, &b.penalty, &[penalty]);
        if let Some(o) = omits {
            write(&gpu, &b.omits, o);
        }
        let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        let count = u32::try_from(pairs.len()).expect("at most 2^32 pairs");
        self.encode_pairs(&mut encoder, &pipeline, count, omits.is_some());
        let b = self.pair_buffers.as_mut().expect("made above");
        b.last = (count, omits.is_some());
        let sent = (size_of_val(pairs) + omits.map_or(0, size_of_val)) as u64;
        gpu.transfers.add(ReadBack::Pairs, Part::Upload, sent, start.elapsed());
        let within = omits.is_some();
        let results = [(&b.out, 0, (8 * OUT * pairs.len()) as u64)];
        submit_and_read_with(&gpu, ReadBack::Pairs, encoder, &results, |bytes| {
            out.par_extend(reals(bytes[0]).par_chunks_exact(OUT).map(|c| convert(bounded_of(c, within))));
        });
        Ok(())
    }
}

impl crate::Bulk {
    /// Records the pair kernel over the first `count` pairs of the kept
    /// buffers (with their thresholds where `within`).
    pub(crate) fn encode_pairs(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        pipeline: &wgpu::ComputePipeline,
        count: u32,
        within: bool,
    ) {
        let b = self.pair_buffers.as_ref().expect("the pairs' buffers");
        let params = Params { count, flags: u32::from(within), pad: [0; 2] };
        let buffers = [&self.x, &self.tets, &b.pairs, &b.penalty, &b.out, &b.omits];
        // Not kept: the count changes from pass to pass.
        dispatch(&self.gpu, None, encoder, pipeline, params, &buffers);
    }

    /// Compiles the pair kernel if it has not been compiled (or refused)
    /// yet: [`Bulk::pair_geometry`] does it at its first call, which a
    /// solver can move out of its first step by calling this first.
    pub fn prepare_pair_kernel(&mut self) {
        if self.pair_kernel.is_none() {
            let gpu = &self.gpu;
            let made = gpu.module("pairs", &kernels::pairs()).and_then(|m| gpu.pipeline("pairs", &m));
            self.pair_kernel = Some(match made {
                Ok(p) => PairKernel::Ready(p),
                Err(e) => PairKernel::Refused(e.to_string()),
            });
        }
    }

    /// The buffer of the pairs' results and the bytes of the last list's,
    /// if the pair kernel ran.
    pub(crate) fn last_pairs_out(&self) -> Option<(&wgpu::Buffer, u64)> {
        let b = self.pair_buffers.as_ref()?;
        (b.last.0 > 0).then(|| (&b.out, (8 * OUT) as u64 * u64::from(b.last.0)))
    }

    /// The pair kernel and the last list it ran on (pairs, thresholds or
    /// not), if it ran.
    pub(crate) fn last_pairs(&self) -> Option<(wgpu::ComputePipeline, u32, bool)> {
        let Some(PairKernel::Ready(p)) = &self.pair_kernel else { return None };
        let (count, within) = self.pair_buffers.as_ref()?.last;
        (count > 0).then(|| (p.clone(), count, within))
    }
}

/// A pair's result from its numbers: negligible where the kernel says so
/// (only with thresholds), else its contact.
fn bounded_of(c: &[Real], within: bool) -> PairBounded {
    if within && c[29] == 1.0 { PairBounded::Negligible(c[28]) } else { PairBounded::Contact(contact_of(c)) }
}
