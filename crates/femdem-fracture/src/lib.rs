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
//! **Architecture invariant:** no mesh, no files, no time stepping: the
//! caller passes positions and history and receives forces and history.

mod coupling;
mod failure;
pub mod heterogeneity;
mod kinematics;
mod law;
mod params;
pub mod softening;

pub use coupling::{Coupling, Softened};
pub use failure::{DOMINANT_SHARE, FailureMode};
pub use kinematics::{GAUSS, JointFrame, JointKinematics, joint_kinematics};
pub use law::{
    Joint, JointHistory, JointOutput, PointStress, joint_update, normal_stress, point_stress, point_stress_with,
};
pub use params::{GfCalibration, JointError, JointParams};
