//! The kernels' own `ln`, `exp`, `ln(1 + x)` and `x − ln(1 + x)` in f64 (`wgsl/math.wgsl`, where the
//! formulas are), evaluated over arrays so that tests can compare them with
//! the CPU's in units in the last place.

use crate::buffers::{Params, dispatch, read, storage, zeroed};
use crate::device::{Gpu, GpuError};
use crate::kernels;

/// Which function [`evaluate`] applies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MathFn {
    /// The natural logarithm (the neo-Hookean `ln J`, Eq. 1).
    Ln,
    /// The exponential (the softening law's curve).
    Exp,
    /// `ln(1 + x)` (the neo-Hookean energy's `ln J`, from `J − 1`).
    Ln1p,
    /// `x − ln(1 + x)` (the neo-Hookean energy's `J − 1 − ln J`).
    Excess,
}

/// `f(x)` for every `x` of `input`, computed on the device.
pub fn evaluate(gpu: &Gpu, f: MathFn, input: &[f64]) -> Result<Vec<f64>, GpuError> {
    let module = gpu.module("math_probe", &kernels::math_probe())?;
    let pipeline = gpu.pipeline("math_probe", &module)?;
    let a = storage(gpu, "math input", input)?;
    let b = zeroed::<f64>(gpu, "math output", input.len())?;
    let mut encoder = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    let flags = match f {
        MathFn::Ln => 0,
        MathFn::Exp => 1,
        MathFn::Ln1p => 2,
        MathFn::Excess => 3,
    };
    let count = u32::try_from(input.len()).expect("at most 2^32 inputs");
    dispatch(gpu, None, &mut encoder, &pipeline, Params { count, flags, pad: [0; 2] }, &[&a, &b]);
    gpu.queue.submit([encoder.finish()]);
    Ok(read(gpu, &b, input.len()))
}

/// How many representable f64 lie between `a` and `b` (0 when equal, both
/// infinite of one sign, or both NaN); `u64::MAX` when one is NaN and the
/// other not. Finite values of opposite signs count through zero.
pub fn ulps_apart(a: f64, b: f64) -> u64 {
    if a.is_nan() || b.is_nan() {
        return if a.is_nan() && b.is_nan() { 0 } else { u64::MAX };
    }
    // Map the floats onto a line of integers ordered as the floats are.
    let key = |x: f64| {
        let bits = x.to_bits() as i64;
        if bits < 0 { i64::MIN - bits } else { bits }
    };
    key(a).abs_diff(key(b))
}
