//! The bulk of femdem's explicit step as compute kernels on a GPU, in
//! double precision (issue 34, part 1).
//!
//! Built on `wgpu` over Vulkan with WGSL kernels in `f64`
//! ([`wgpu::Features::SHADER_F64`]): the same code runs on a GPU and, for
//! tests, on Mesa's lavapipe, a Vulkan device on the CPU. What is here:
//!
//! - [`Gpu`]: the adapter, refused with a clear [`GpuError`] when it has
//!   no 64-bit floats;
//! - [`math`]: the kernels' own `ln` and `exp` (Vulkan's are single
//!   precision), with their formulas in `wgsl/math.wgsl`;
//! - [`Bulk`]: the tet pass of Eq. 1–2 (`femdem_material::tet_forces` on
//!   the device: `wgsl/tets.wgsl`) and the gather of each node's slots in
//!   the CPU's fixed order (`wgsl/gather.wgsl`).
//!
//! - the joint pass of Eq. 3–13 (`femdem_fracture::joint_update_fast` on
//!   the device: `wgsl/joints.wgsl`), histories kept on the device.
//!
//! - [`motion`]: the update, the energy sums (in the CPU's chunk order)
//!   and the drives' nodes' state, and [`surface`]: pressures and
//!   tractions on the current geometry, so that positions and velocities
//!   stay on the device.
//!
//! - [`pairs`]: the potential contact force of Eq. 17 between pairs of
//!   tets (`femdem_contact::tet_tet_contact` and, with a threshold,
//!   `tet_tet_contact_within` on the device), checked pair by pair against
//!   the CPU; `Bulk::pair_geometry` computes it at the device's positions
//!   for the solver's contact pass.
//!
//! The solver's switch to this path is `femdem_solver::Solver::use_device`
//! (`[solver] device = "gpu"`, `femdem run --device gpu`). Not yet here:
//! the rest of the contact pass (issue 35: detection, friction, the
//! activation and the sums into nodal forces run on the CPU beside the
//! device).
//!
//! This crate knows the material law and the tet's reference shape
//! (`femdem-material`) and nothing of the solver or the case files; of
//! contact, only the pair force's formula (its tests compare it with
//! `femdem-contact`'s).

mod buffers;
pub mod bulk;
pub mod device;
mod joints;
mod kernels;
pub mod math;
pub mod motion;
pub mod pairs;
mod staging;
pub mod surface;
pub mod timings;
pub mod transfers;

pub use bulk::{Bulk, Evaluate, TetMesh};
pub use device::{Gpu, GpuError};
pub use joints::JointMesh;
pub use motion::{MotionSetup, Resident, Sum, Totals};
pub use surface::{LoadSums, SurfaceKind, SurfaceLoad};
pub use timings::Timing;
pub use transfers::{Part, Phase, ReadBack};
