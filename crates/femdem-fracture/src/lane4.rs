//! Four `f64` lanes as a plain array, for [`crate::lanes`].
//!
//! Every operation is written lane by lane over `[f64; 4]`, so the
//! compiler packs it into whatever vector unit the code is compiled for:
//! two SSE2 registers in a baseline x86-64 build, one AVX register where a
//! caller compiles it for x86-64-v3 (`femdem_solver`'s run-time dispatch).
//! (`wide::f64x4`, used before, fixes its width when the crate is built, so
//! a dispatched caller could not widen it.) Each lane is the IEEE-754
//! operation of the scalar code, never a fused multiply-add, so the results
//! are the scalar ones bit for bit on every path.

use std::ops::{Add, AddAssign, BitAnd, Div, Mul, Sub};

/// Four `f64` values, one per lane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct F4(pub [f64; 4]);

/// Four lane conditions, each all ones (true) or all zeros (false), as a
/// vector unit's comparisons give them, so that [`M4::select`] is three
/// bitwise operations rather than a branch per lane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct M4([u64; 4]);

impl F4 {
    pub const ZERO: F4 = F4([0.0; 4]);

    #[inline(always)]
    pub fn splat(v: f64) -> F4 {
        F4([v; 4])
    }
    #[inline(always)]
    fn zip(self, o: F4, f: impl Fn(f64, f64) -> f64) -> F4 {
        F4([f(self.0[0], o.0[0]), f(self.0[1], o.0[1]), f(self.0[2], o.0[2]), f(self.0[3], o.0[3])])
    }
    #[inline(always)]
    fn test(self, o: F4, f: impl Fn(f64, f64) -> bool) -> M4 {
        let m = |a, b| if f(a, b) { u64::MAX } else { 0 };
        M4([m(self.0[0], o.0[0]), m(self.0[1], o.0[1]), m(self.0[2], o.0[2]), m(self.0[3], o.0[3])])
    }
    #[inline(always)]
    pub fn sqrt(self) -> F4 {
        F4(self.0.map(f64::sqrt))
    }
    #[inline(always)]
    pub fn simd_lt(self, o: F4) -> M4 {
        self.test(o, |a, b| a < b)
    }
    #[inline(always)]
    pub fn simd_gt(self, o: F4) -> M4 {
        self.test(o, |a, b| a > b)
    }
    #[inline(always)]
    pub fn as_array(&self) -> &[f64; 4] {
        &self.0
    }
}

impl M4 {
    /// `a` where the lane's condition holds, `b` elsewhere.
    #[inline(always)]
    pub fn select(self, a: F4, b: F4) -> F4 {
        let pick = |m: u64, a: f64, b: f64| f64::from_bits((a.to_bits() & m) | (b.to_bits() & !m));
        let m = self.0;
        F4([
            pick(m[0], a.0[0], b.0[0]),
            pick(m[1], a.0[1], b.0[1]),
            pick(m[2], a.0[2], b.0[2]),
            pick(m[3], a.0[3], b.0[3]),
        ])
    }
    /// Whether every lane's condition holds.
    #[inline(always)]
    pub fn all(self) -> bool {
        self.0[0] & self.0[1] & self.0[2] & self.0[3] == u64::MAX
    }
}

impl From<[f64; 4]> for F4 {
    #[inline(always)]
    fn from(v: [f64; 4]) -> F4 {
        F4(v)
    }
}

impl Add for F4 {
    type Output = F4;
    #[inline(always)]
    fn add(self, o: F4) -> F4 {
        self.zip(o, |a, b| a + b)
    }
}
impl AddAssign for F4 {
    #[inline(always)]
    fn add_assign(&mut self, o: F4) {
        *self = *self + o;
    }
}
impl Sub for F4 {
    type Output = F4;
    #[inline(always)]
    fn sub(self, o: F4) -> F4 {
        self.zip(o, |a, b| a - b)
    }
}
impl Mul for F4 {
    type Output = F4;
    #[inline(always)]
    fn mul(self, o: F4) -> F4 {
        self.zip(o, |a, b| a * b)
    }
}
impl Div for F4 {
    type Output = F4;
    #[inline(always)]
    fn div(self, o: F4) -> F4 {
        self.zip(o, |a, b| a / b)
    }
}
impl BitAnd for M4 {
    type Output = M4;
    #[inline(always)]
    fn bitand(self, o: M4) -> M4 {
        M4([self.0[0] & o.0[0], self.0[1] & o.0[1], self.0[2] & o.0[2], self.0[3] & o.0[3]])
    }
}
