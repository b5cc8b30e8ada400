//! Four `f64` lanes as a plain array, for kernels that evaluate four
//! elements at once (the joint lanes of `femdem-fracture`, the tet lanes of
//! `femdem-material`).
//!
//! Every operation is written lane by lane over `[f64; 4]` and marked
//! `#[inline(always)]`, so the compiler packs it into whatever vector unit
//! the calling code is compiled for: two SSE2 registers in a baseline
//! x86-64 build, one AVX register where a caller is compiled for x86-64-v3
//! (`femdem_solver`'s run-time dispatch). (`wide::f64x4`, used before,
//! fixes its width when the crate is built, so a dispatched caller could not
//! widen it.) Each lane is the IEEE-754 operation of the scalar code, never
//! a fused multiply-add, so a kernel that does the scalar code's operations
//! in the scalar code's order gives its results bit for bit on every path.
//!
//! [`F4x3`]'s products follow nalgebra's order (`dot` is
//! `(x x′ + y y′) + z z′`, `cross` term for term), so that lane kernels can
//! match the nalgebra code they stand in for.

use crate::Vec3;

use std::ops::{Add, AddAssign, BitAnd, Div, Mul, Neg, Sub};

/// Four `f64` values, one per lane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct F4(pub [f64; 4]);

/// Four lane conditions, each all ones (true) or all zeros (false), as a
/// vector unit's comparisons give them, so that [`M4::select`] is three
/// bitwise operations rather than a branch per lane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct M4([u64; 4]);

impl F4 {
    /// Zero in every lane.
    pub const ZERO: F4 = F4([0.0; 4]);

    /// `v` in every lane.
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
    /// `√` lane by lane.
    #[inline(always)]
    pub fn sqrt(self) -> F4 {
        self.each(f64::sqrt)
    }
    /// `self < o` lane by lane.
    #[inline(always)]
    pub fn simd_lt(self, o: F4) -> M4 {
        self.test(o, |a, b| a < b)
    }
    /// `self > o` lane by lane.
    #[inline(always)]
    pub fn simd_gt(self, o: F4) -> M4 {
        self.test(o, |a, b| a > b)
    }
    /// The four values.
    #[inline(always)]
    pub fn as_array(&self) -> &[f64; 4] {
        &self.0
    }
    /// `f64::max` lane by lane (the other operand where one is NaN).
    #[inline(always)]
    pub fn max(self, o: F4) -> F4 {
        self.zip(o, f64::max)
    }
    /// `f64::ln` lane by lane (four calls of the scalar function, so the
    /// same bits as the scalar code).
    #[inline(always)]
    pub fn ln(self) -> F4 {
        self.each(f64::ln)
    }
    /// `f` lane by lane, written out (`array::map` is not always inlined,
    /// which would take it out of a dispatched caller's instruction set).
    #[inline(always)]
    fn each(self, f: impl Fn(f64) -> f64) -> F4 {
        F4([f(self.0[0]), f(self.0[1]), f(self.0[2]), f(self.0[3])])
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
impl Neg for F4 {
    type Output = F4;
    #[inline(always)]
    fn neg(self) -> F4 {
        self.each(|a| -a)
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

/// Three lanes of vectors, component by component.
#[derive(Clone, Copy)]
pub struct F4x3 {
    /// The x components.
    pub x: F4,
    /// The y components.
    pub y: F4,
    /// The z components.
    pub z: F4,
}

// Named methods rather than operator traits, so the kernels written on
// them read as the nalgebra code they stand in for (`a.add(b)`).
#[allow(clippy::should_implement_trait)]
impl F4x3 {
    /// Zero in every lane.
    #[inline(always)]
    pub fn zero() -> F4x3 {
        F4x3 { x: F4::ZERO, y: F4::ZERO, z: F4::ZERO }
    }
    /// The four vectors `v`, one a lane.
    #[inline(always)]
    pub fn gather(v: [Vec3; 4]) -> F4x3 {
        F4x3 {
            x: F4::from([v[0].x, v[1].x, v[2].x, v[3].x]),
            y: F4::from([v[0].y, v[1].y, v[2].y, v[3].y]),
            z: F4::from([v[0].z, v[1].z, v[2].z, v[3].z]),
        }
    }
    /// Lane `l`'s vector.
    #[inline(always)]
    pub fn lane(&self, l: usize) -> Vec3 {
        Vec3::new(self.x.as_array()[l], self.y.as_array()[l], self.z.as_array()[l])
    }
    /// `self + o`.
    #[inline(always)]
    pub fn add(self, o: F4x3) -> F4x3 {
        F4x3 { x: self.x + o.x, y: self.y + o.y, z: self.z + o.z }
    }
    /// `self − o`.
    #[inline(always)]
    pub fn sub(self, o: F4x3) -> F4x3 {
        F4x3 { x: self.x - o.x, y: self.y - o.y, z: self.z - o.z }
    }
    /// `self s`, lane by lane.
    #[inline(always)]
    pub fn scale(self, s: F4) -> F4x3 {
        F4x3 { x: self.x * s, y: self.y * s, z: self.z * s }
    }
    /// `self / s`, lane by lane.
    #[inline(always)]
    pub fn div(self, s: F4) -> F4x3 {
        F4x3 { x: self.x / s, y: self.y / s, z: self.z / s }
    }
    /// nalgebra's order: `(x x′ + y y′) + z z′`.
    #[inline(always)]
    pub fn dot(self, o: F4x3) -> F4 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    /// nalgebra's cross product, term for term.
    #[inline(always)]
    pub fn cross(self, b: F4x3) -> F4x3 {
        F4x3 { x: self.y * b.z - self.z * b.y, y: self.z * b.x - self.x * b.z, z: self.x * b.y - self.y * b.x }
    }
    /// The Euclidean norm, `√(self · self)`.
    #[inline(always)]
    pub fn norm(self) -> F4 {
        self.dot(self).sqrt()
    }
    /// `a` in the lanes where `mask` holds, `b` elsewhere.
    #[inline(always)]
    pub fn select(mask: M4, a: F4x3, b: F4x3) -> F4x3 {
        F4x3 { x: mask.select(a.x, b.x), y: mask.select(a.y, b.y), z: mask.select(a.z, b.z) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each lane is the scalar operation's result, bit for bit (signed
    /// zeros and infinities included), and a select keeps the chosen
    /// operand's bits.
    #[test]
    fn lanes_are_the_scalar_operations() {
        let a = F4([1.5, -0.0, f64::INFINITY, 3e-310]);
        let b = F4([-2.25, 0.0, 1.0, 7.0]);
        let bits = |v: F4| v.0.map(f64::to_bits);
        for (lanes, scalar) in [
            (a + b, [0, 1, 2, 3].map(|l| a.0[l] + b.0[l])),
            (a - b, [0, 1, 2, 3].map(|l| a.0[l] - b.0[l])),
            (a * b, [0, 1, 2, 3].map(|l| a.0[l] * b.0[l])),
            (a / b, [0, 1, 2, 3].map(|l| a.0[l] / b.0[l])),
            (-a, [0, 1, 2, 3].map(|l| -a.0[l])),
            (a.max(b), [0, 1, 2, 3].map(|l| a.0[l].max(b.0[l]))),
            (b.sqrt(), [0, 1, 2, 3].map(|l| b.0[l].sqrt())),
        ] {
            assert_eq!(bits(lanes), scalar.map(f64::to_bits));
        }
        let lt = a.simd_lt(b);
        assert_eq!(bits(lt.select(a, b)), [b.0[0], b.0[1], b.0[2], a.0[3]].map(f64::to_bits));
        assert!(!lt.all());
        assert!(F4::splat(-1.0).simd_lt(F4::ZERO).all());
        assert!(!F4::splat(f64::NAN).simd_gt(F4::ZERO).all(), "a NaN lane fails a comparison");
    }
}
