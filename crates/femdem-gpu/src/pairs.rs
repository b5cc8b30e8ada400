//! The potential contact force of Eq. 17 between pairs of tets on the
//! device (`wgsl/pairs.wgsl`): `femdem_contact::tet_tet_contact` (the
//! reference clipping, no face left out) one pair per invocation, the
//! first brick of contact on the device (issue 35). What the solver's
//! contact pass adds to it — friction, the start-at-zero activation, the
//! skipped and certified pairs, the sum into nodal forces — is not here
//! yet.

use femdem_core::{Real, Vec3};

use crate::buffers::{Params, dispatch, read, storage, zeroed};
use crate::device::{Gpu, GpuError};
use crate::kernels;

/// Numbers the kernel writes per pair: forces on `a`'s and `b`'s nodes,
/// `Σ |F_k| P_k` and `Σ |F_k|`.
const OUT: usize = 28;

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

/// The contacts of `pairs` (indices into `tets`, whose nodes index `x`)
/// at penalty `penalty` (Pa), computed on the device in one dispatch.
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
    let module = gpu.module("pairs", &kernels::pairs())?;
    let pipeline = gpu.pipeline("pairs", &module)?;
    let flat: Vec<Real> = x.iter().flat_map(|p| [p.x, p.y, p.z]).collect();
    let xb = storage(gpu, "contact positions", &flat)?;
    let tb = storage(gpu, "contact tets", tets.as_flattened())?;
    let pb = storage(gpu, "contact pairs", pairs.as_flattened())?;
    let sb = storage(gpu, "contact penalty", &[penalty])?;
    let ob = zeroed::<Real>(gpu, "pair contacts", OUT * pairs.len())?;
    let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    let count = u32::try_from(pairs.len()).expect("at most 2^32 pairs");
    dispatch(gpu, None, &mut encoder, &pipeline, Params { count, flags: 0, pad: [0; 2] }, &[&xb, &tb, &pb, &sb, &ob]);
    gpu.queue.submit([encoder.finish()]);
    let out: Vec<Real> = read(gpu, &ob, OUT * pairs.len());
    Ok(out
        .chunks_exact(OUT)
        .map(|c| {
            let v = |k: usize| Vec3::new(c[3 * k], c[3 * k + 1], c[3 * k + 2]);
            let (moment, weight) = (v(8), c[27]);
            PairContact {
                on_a: std::array::from_fn(v),
                on_b: std::array::from_fn(|k| v(4 + k)),
                centre: (weight > 0.0).then(|| moment / weight),
                weight,
            }
        })
        .collect())
}
