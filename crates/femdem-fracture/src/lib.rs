//! Cohesive joint elements of the combined finite–discrete element method
//! (reference paper §2.2, Fig. 2–3, Eq. 3–13).
//!
//! A joint `N1 N2 N3 – N4 N5 N6` ties the face `N1 N2 N3` of one tet to the
//! coincident face `N4 N5 N6` of its neighbour (`N1–N6`, `N2–N5`, `N3–N4`
//! start at the same point). This crate computes, from the six current node
//! positions, a joint's parameters and its damage history, the opening and
//! slip at its three integration points (Eq. 3), the tractions of the
//! stress–displacement law (Eq. 5–13: hardening to the peak, Munjiza's
//! softening, Mohr–Coulomb shear strength with tension cut-off, fracture
//! energy), the nodal forces, the new history, and whether the joint has
//! failed — a pure function that another solver can call. It also samples
//! heterogeneous strengths.
//!
//! # Code map
//!
//! - [`joint_kinematics`] (`kinematics.rs`): the `x′y′z′` frame through the
//!   mid-points N16, N25, N34 (Fig. 2), Hammer's three points ([`GAUSS`]),
//!   opening `δn` and slip `δs` (Eq. 3).
//! - [`JointParams`] (`params.rs`): `p0`, `f_t`, `c`, `φ`, `G_ft`, `G_fs`,
//!   the Gf calibration of Eq. 10 and the [`Coupling`]; validation.
//! - [`Joint`], [`point_stress`], [`joint_update`] (`law.rs`): Eq. 5–7,
//!   Eq. 11 branches, Eq. 13 damage with its irreversible history
//!   ([`JointHistory`]), nodal forces, work and stored energy, failure when
//!   two of three points carry no stress.
//! - [`joint_update_fast`] (`kernel.rs`): the same, bit for bit, for the
//!   force pass: `z` only where the damage is not zero and changed, the
//!   stored energy only when asked for or released.
//! - [`joint_update_lanes`] (`lanes.rs`): four intact joints in SIMD lanes
//!   (`femdem_core::lanes`: four `f64` a lane group), bit for bit the same, for the elastic regime.
//! - [`Coupling`] (`coupling.rs`): how damage acts on the hardening branches
//!   of Eq. 11 (capped, as printed, multiplicative).
//! - [`FailureMode`] (`failure.rs`): the label of a failure, from the shares
//!   of the normal and shear softening in Eq. 13's `D²`.
//! - [`softening`]: Munjiza's `z(D)` (Eq. 12) and its integral.
//! - [`heterogeneity`]: random strength factors (Weibull or normal).
//!
//! # Conventions
//!
//! SI units (m, Pa, J/m²); angles in radians. The opening `δn` is positive
//! when side b (`N4 N5 N6`) has moved from side a (`N1 N2 N3`) along `z′`,
//! the normal `(N25 − N16) × (N34 − N16)`; the normal stress is positive in
//! tension. Forces are those the joint applies to its six nodes (they sum
//! to zero); an open joint pulls its faces together.
//!
//! **Architecture invariant:** no mesh, no files, no time stepping: the
//! caller passes positions and history and receives forces and history.
//!
//! # Example
//!
//! A joint of the paper's Table 1 opened to half its peak displacement
//! carries `σ = (2 · ½ − ¼) f_t = 0.75 f_t` on its hardening branch (Eq. 11);
//! opened past `δnc` it fails in tension and carries nothing.
//!
//! ```
//! use femdem_core::Vec3;
//! use femdem_fracture::{Coupling, FailureMode, GfCalibration, Joint, JointHistory, JointParams, joint_update};
//!
//! let params = JointParams {
//!     penalty: 2.6e11,
//!     tensile_strength: 3e6,
//!     cohesion: 15e6,
//!     friction_angle: 30f64.to_radians(),
//!     gf_tension: 50.0,
//!     gf_shear: 50.0,
//!     calibration: GfCalibration::Paper,
//!     coupling: Coupling::Capped,
//! }
//! .validate()?;
//! let a = [Vec3::zeros(), Vec3::new(1e-3, 0.0, 0.0), Vec3::new(0.0, 1e-3, 0.0)];
//! let h = (1e-3 + 1e-3 + 2f64.sqrt() * 1e-3) / 3.0; // mean edge
//! let joint = Joint::new(params, h);
//! let opened = |dn: f64| {
//!     let d = Vec3::new(0.0, 0.0, dn);
//!     [a[0], a[1], a[2], a[2] + d, a[1] + d, a[0] + d]
//! };
//! let mut history = JointHistory::default();
//! let out = joint_update(&joint, &mut history, &opened(0.5 * joint.delta_np), false);
//! let on_b: f64 = out.forces[3..].iter().map(|f| f.z).sum();
//! let area = 0.5e-6;
//! assert!((on_b / (-0.75 * 3e6 * area) - 1.0).abs() < 1e-9);
//!
//! let out = joint_update(&joint, &mut history, &opened(1.01 * joint.delta_nc), false);
//! assert_eq!(out.failed, Some(FailureMode::Tensile));
//! assert!(out.forces.iter().all(|f| f.norm() == 0.0));
//! # Ok::<(), femdem_fracture::JointError>(())
//! ```

mod coupling;
mod failure;
pub mod heterogeneity;
mod kernel;
mod kinematics;
mod lanes;
mod law;
mod params;
pub mod softening;

pub use coupling::{Coupling, Softened};
pub use failure::{DOMINANT_SHARE, FailureMode};
pub use kernel::{KernelConsts, joint_update_fast};
pub use kinematics::{GAUSS, JointFrame, JointKinematics, joint_kinematics};
pub use lanes::{LANES, joint_update_lanes};
pub use law::{
    Joint, JointHistory, JointOutput, PointStress, joint_update, normal_stress, point_stress, point_stress_with,
};
pub use params::{GfCalibration, JointError, JointParams};
