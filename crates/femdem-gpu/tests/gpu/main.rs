//! The device kernels against the CPU's, on whatever Vulkan adapter with
//! 64-bit floats the machine has (lavapipe in CI, installed by `.ci/run`).
//!
//! Where no such adapter exists the tests say so and pass, unless
//! `FEMDEM_GPU_REQUIRED` is set (as `.ci/run` sets it): then a missing
//! adapter fails them.

mod joints;
mod math;
mod pairs;
mod tets;

use femdem_gpu::Gpu;

/// The device, or `None` where the machine has none and
/// `FEMDEM_GPU_REQUIRED` is not set ([`Gpu::for_tests`]).
pub fn gpu() -> Option<Gpu> {
    Gpu::for_tests()
}
