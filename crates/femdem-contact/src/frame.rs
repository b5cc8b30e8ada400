//! Where the pair kernel's large functions run: [`Frame`].
//!
//! The kernel (Eq. 17's clipping, its sub-tet tournament, the bound on a
//! pair's forces) is scalar code that a compiler packs better for a wider
//! vector unit (three-operand AVX forms, wider moves): built whole for
//! x86-64-v3 its loop ran in 0.91 of the time (`docs/performance.md`). A
//! binary built for baseline x86-64 can have that only where each function
//! is compiled a second time with the wider unit's features, and a function
//! so compiled must not be inlined into one that is not, nor call large
//! functions compiled without them.
//!
//! So each large function of the kernel runs through a frame: its body is
//! inlined into [`Frame::call`]'s work, and the frame runs that work in a
//! function of its own — compiled for the frame's instruction set — which
//! calls the next large function through the same frame. [`Plain`] is the
//! baseline: each call a function of its own (as the functions were), no
//! new features. A solver that knows the processor (femdem's
//! `femdem-solver`, with `pulp`) supplies a frame compiled for a wider
//! unit, so that this crate needs neither `unsafe` nor a dependency to
//! choose one.
//!
//! **Same numbers in every frame.** A frame may change how instructions
//! are encoded and registers used, never the operations: Rust never
//! contracts `a * b + c` into a fused multiply-add, and the kernel calls no
//! `mul_add`, so every frame computes the same IEEE-754 operations in the
//! same order and gives the same bits (the solver's tests run both).

/// The frame that runs a kernel function (the module documentation).
pub trait Frame: Copy + Send + Sync {
    /// Runs `work` with this frame, in a function of its own compiled for
    /// the frame's instruction set. `work` must be `#[inline(always)]` down
    /// to the arithmetic (what it calls without inlining is compiled
    /// without the frame's features), and calls the large functions it
    /// needs through the frame it is given.
    fn call<R>(self, work: impl FnOnce(Self) -> R) -> R;
}

/// The baseline frame: each call a function of its own, compiled as the
/// binary is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Plain;

impl Frame for Plain {
    #[inline(always)]
    fn call<R>(self, work: impl FnOnce(Self) -> R) -> R {
        out_of_line(work)
    }
}

/// [`Plain::call`]'s function of its own (so that its work, inlined into
/// it, is not inlined further into the caller: the body of each kernel
/// function stays one function, as the compiler laid it out before frames).
#[inline(never)]
fn out_of_line<R>(work: impl FnOnce(Plain) -> R) -> R {
    work(Plain)
}
