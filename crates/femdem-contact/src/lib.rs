//! Contact detection for the combined finite–discrete element method
//! (reference paper §2.3).
//!
//! Today: the broad phase, [`Nbs`] — the NBS ("no binary search") algorithm
//! of Munjiza & Andrews (1998) for bodies of similar size, which finds every
//! pair of bounding spheres that overlap in time and memory linear in the
//! number of elements — and the normal force of the tet–tet penalty
//! potential contact, [`tet_tet_forces`] (Eq. 17). Friction, the Eq. 18 ramp,
//! the activation on fracture (Eq. 14–16) and the solver's contact pass are
//! the rest of the contact issue.
//!
//! **Architecture invariant:** no mesh, no files, no time stepping: the
//! caller passes spheres and receives pairs.

mod nbs;
mod potential;

pub use nbs::Nbs;
pub use potential::tet_tet_forces;
