//! Explicit time integration of the combined finite–discrete element
//! method (reference paper §2.4, Eq. 19–20): lumped masses, the
//! central-difference update, loads with the paper's ramp, rigid platens as
//! velocity drives with recorded reactions, the stable time step, and the
//! energy account.
//!
//! **Architecture invariant:** no files, no terminal, no case format: the
//! caller builds a [`Model`] and [`Loads`] and calls [`Solver::step`].
//! Results are identical bit for bit for any number of threads.

pub mod contact;
mod error;
pub mod forces;
mod integrate;
pub mod loads;
mod model;
pub mod select;
mod timestep;

pub use contact::{Contact, ContactSettings, RAMP_STEPS};
pub use error::SolverError;
pub use forces::{ForceSums, Want, Workspace};
pub use integrate::{Energies, Failure, Solver, State, StepReport};
pub use loads::{Fixed, Loads, Ramp, SurfaceKind, SurfaceLoad, VelocityDrive};
pub use model::{Gather, Model, RIGID, RegionBehaviour};
pub use timestep::{StableStep, contact_omega, element_transit, stable_time_step};
