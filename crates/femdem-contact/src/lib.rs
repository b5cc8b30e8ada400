//! Contact detection for the combined finite–discrete element method
//! (reference paper §2.3).
//!
//! Two stateless pieces another solver can use on their own: the broad
//! phase, [`Nbs`] — the NBS ("no binary search") algorithm of Munjiza &
//! Andrews (1998) for bodies of similar size, which finds every pair of
//! bounding spheres that overlap in time and memory linear in the number of
//! elements — and the normal force of the tet–tet penalty potential
//! contact, [`tet_tet_forces`] (Eq. 17; [`tet_tet_contact`] adds the point
//! where it acts). What needs history — Coulomb
//! friction, the Eq. 18 ramp, the activation on fracture (Eq. 14–16) — is
//! the solver's contact pass (`femdem-solver`, module `contact`).
//!
//! **Architecture invariant:** no mesh, no files, no time stepping: the
//! caller passes spheres and receives pairs.

mod nbs;
mod potential;

pub use nbs::Nbs;
pub use potential::{TetTetContact, tet_tet_contact, tet_tet_forces};
