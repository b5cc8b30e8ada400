//! Contact detection for the combined finite–discrete element method
//! (reference paper §2.3).
//!
//! Today: the broad phase, [`Nbs`] — the NBS ("no binary search") algorithm
//! of Munjiza & Andrews (1998) for bodies of similar size, which finds every
//! pair of bounding spheres that overlap in time and memory linear in the
//! number of elements. The narrow phase (tet–tet penalty potential, Eq. 17),
//! friction, the Eq. 18 ramp and the activation on fracture (Eq. 14–16) are
//! the rest of the contact issue.
//!
//! **Architecture invariant:** no mesh, no files, no time stepping: the
//! caller passes spheres and receives pairs.

mod nbs;

pub use nbs::Nbs;
