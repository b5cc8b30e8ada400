//! The widest vector unit the processor has, chosen at run time.
//!
//! A binary built for baseline x86-64 may only use SSE2 (two `f64` a
//! register), yet most machines that run femdem have AVX2 (four). [`widest`] runs a
//! [`Pass`] compiled a second time for x86-64-v3 (AVX, AVX2, FMA, BMI1/2,
//! F16C, LZCNT, MOVBE) when the processor has it, through `pulp`'s
//! `Simd::vectorize`, which keeps the `unsafe` of `#[target_feature]` inside
//! `pulp`. The code inlined into a [`Pass`] is compiled for those features;
//! functions it calls without inlining are not.
//!
//! # Same numbers on every path
//!
//! Rust never contracts `a * b + c` into a fused multiply-add (no
//! floating-point contraction without an explicit `mul_add`), and the
//! kernels call no `mul_add`; the wider unit only packs the same IEEE-754
//! operations, in the same order, into wider registers. Both paths therefore
//! give identical bits, which the tests check by running each pass on both
//! ([`VectorPath::Baseline`] forces the baseline).
//!
//! The tet and joint passes are dispatched; what gains is their lanes
//! (`femdem_material::tet_lanes`, `femdem_fracture`'s `lanes.rs`, on
//! `femdem_core::lanes`), written to be packed: scalar `nalgebra` code
//! compiled for x86-64-v3 ran no faster (`docs/performance.md`).
//!
//! The contact pair kernel is scalar too, but branchy and large, and gains
//! from the wider unit's encodings themselves (three-operand forms, wider
//! moves): it runs through [`Wide`], a `femdem_contact::Frame` that
//! compiles each of the kernel's large functions for x86-64-v3 as a
//! function of its own (inlined into one body per pass, it ran 1.33×
//! slower: `docs/performance.md`).

/// Which compilation of a pass runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VectorPath {
    /// The widest the processor has (x86-64-v3 where available).
    Widest,
    /// The baseline build's own code, whatever the processor has.
    Baseline,
}

/// A pass to run on [`widest`]: its work, in [`Pass::run`], must be
/// `#[inline(always)]` all the way down to the arithmetic, so that each
/// compilation of it is compiled for its own instruction set.
pub(crate) trait Pass {
    /// What the pass returns.
    type Output;
    /// The pass's work.
    fn run(self) -> Self::Output;
}

/// `pulp`'s handle on a [`Pass`]: `with_simd` is generic over the
/// instruction set, so each set gets its own monomorphised, inlined copy.
struct Op<P>(P);

impl<P: Pass> pulp::WithSimd for Op<P> {
    type Output = P::Output;
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) -> P::Output {
        self.0.run()
    }
}

/// Runs `pass` on `path`: compiled for x86-64-v3 where `path` is
/// [`VectorPath::Widest`] and the processor has it, as built otherwise.
#[inline(always)]
pub(crate) fn widest<P: Pass>(path: VectorPath, pass: P) -> P::Output {
    #[cfg(target_arch = "x86_64")]
    if path == VectorPath::Widest
        && let Some(v3) = pulp::x86::V3::try_new()
    {
        return pulp::Simd::vectorize(v3, Op(pass));
    }
    let _ = path;
    pulp::Simd::vectorize(pulp::Scalar::new(), Op(pass))
}

/// The pair kernel's frame on x86-64-v3 (`femdem_contact::Frame`): each
/// large function of the kernel compiled for AVX2 in a function of its
/// own, entered through `pulp`'s `vectorize` on a token proved once (no
/// feature detection per call).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Wide(#[cfg(target_arch = "x86_64")] pulp::x86::V3);

impl Wide {
    /// The frame for `path`, where it is [`VectorPath::Widest`] and the
    /// processor has x86-64-v3; `None` where the baseline runs.
    pub(crate) fn new(path: VectorPath) -> Option<Wide> {
        #[cfg(target_arch = "x86_64")]
        if path == VectorPath::Widest {
            return pulp::x86::V3::try_new().map(Wide);
        }
        let _ = path;
        None
    }
}

/// `pulp`'s handle on a frame's work.
struct FrameOp<W>(W, Wide);

impl<R, W: FnOnce(Wide) -> R> pulp::WithSimd for FrameOp<W> {
    type Output = R;
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) -> R {
        (self.0)(self.1)
    }
}

impl femdem_contact::Frame for Wide {
    #[inline(always)]
    fn call<R>(self, work: impl FnOnce(Self) -> R) -> R {
        #[cfg(target_arch = "x86_64")]
        return pulp::Simd::vectorize(self.0, FrameOp(work, self));
        #[cfg(not(target_arch = "x86_64"))]
        return pulp::Simd::vectorize(pulp::Scalar::new(), FrameOp(work, self));
    }
}

/// The name of the unit [`widest`] uses on this processor (the run
/// summary's `throughput` line names it).
pub fn widest_name() -> &'static str {
    #[cfg(target_arch = "x86_64")]
    if pulp::x86::V3::try_new().is_some() {
        return "x86-64-v3 (AVX2)";
    }
    "baseline"
}
