//! Cohesive joint elements of the combined finite–discrete element method
//! (reference paper §2.2, Fig. 2–3, Eq. 3–13).
//!
//! A joint `N1 N2 N3 – N4 N5 N6` ties the face `N1 N2 N3` of one tet to the
//! coincident face `N4 N5 N6` of its neighbour (`N1–N6`, `N2–N5`, `N3–N4`
//! start at the same point). This crate computes, from the six current node
//! positions and a joint's parameters, the opening and slip at its three
//! integration points, the tractions of the stress–displacement law, and the
//! nodal forces — a pure function that another solver can call.
//!
//! **Architecture invariant:** no mesh, no files, no time stepping: the
//! caller passes positions and receives forces.
//!
//! Status: the kinematics and the intact branches of Eq. 11 (compression and
//! hardening up to the peak) are implemented; beyond the peak the traction
//! is held at the peak until the softening and failure of the cohesive
//! fracture issue land.

mod kinematics;
mod law;
mod params;

pub use kinematics::{GAUSS, JointFrame, JointKinematics, joint_kinematics};
pub use law::{IntactJoint, JointForces, joint_forces, normal_stress, shear_stress};
pub use params::{JointError, JointParams};
