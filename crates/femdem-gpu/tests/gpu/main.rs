//! The device kernels against the CPU's, on whatever Vulkan adapter with
//! 64-bit floats the machine has (lavapipe in CI, installed by `.ci/run`).
//!
//! Where no such adapter exists the tests say so and pass, unless
//! `FEMDEM_GPU_REQUIRED` is set (as `.ci/run` sets it): then a missing
//! adapter fails them.

mod joints;
mod math;
mod tets;

use femdem_gpu::Gpu;

/// The device, or `None` (with a line on stderr) where the machine has no
/// usable adapter and `FEMDEM_GPU_REQUIRED` is not set.
pub fn gpu() -> Option<Gpu> {
    match Gpu::new() {
        Ok(g) => Some(g),
        Err(e) if std::env::var_os("FEMDEM_GPU_REQUIRED").is_none() => {
            eprintln!("no device, GPU test not run: {e}");
            None
        }
        Err(e) => panic!("FEMDEM_GPU_REQUIRED is set and no device opened: {e}"),
    }
}
