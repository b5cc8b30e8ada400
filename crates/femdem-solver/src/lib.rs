//! Explicit time integration of the combined finite–discrete element
//! method (reference paper §2.4, Eq. 19–20): lumped masses, the
//! central-difference update, loads with the paper's ramp, rigid platens as
//! velocity drives with recorded reactions, the contact pass (§2.3), the
//! stable time step, and the energy account.
//!
//! # Code map
//!
//! - [`Model`] (`model.rs`): reference positions, lumped masses, per-tet
//!   reference data and material, per-joint law, node→slot gather tables.
//! - [`Loads`] (`loads.rs`): fixed components, velocity drives, surface
//!   loads, gravity, ramps; node and face selection in [`select`].
//! - [`stable_time_step`] (`timestep.rs`): the critical step of the model.
//! - [`Solver`] (`step/`): the state ([`State`]), the energy account
//!   ([`Energies`]), the failure record ([`Failure`]) and [`Solver::step`],
//!   which runs the stages of one step — internal forces (`forces.rs`),
//!   failures, contact (`contact/`), external forces, update, energy — and
//!   returns a [`StepRecord`] of step `n`.
//! - `ledger.rs`: every work and energy term with the half step it holds
//!   over between steps, the external work as the sum of its terms, and
//!   the watch on the balance ([`Solver::imbalance`], [`Imbalance`]).
//! - [`Solver::snapshot`] / [`Solver::restore`] (`snapshot.rs`): the
//!   evolving state as bytes, for checkpoints; a restored solver continues
//!   bit for bit.
//!
//! # Conventions
//!
//! SI units throughout (m, s, kg, N, Pa, J). Tension is positive. Forces in
//! a [`StepRecord`] are those the solver applies (a platen's reaction is the
//! force the platen exerts on the body). A step evaluates everything at
//! `t_n` and then moves the nodes to `t_{n+1}`: the record and the stresses
//! belong to `t_n`, [`Solver::state`] to `t_{n+1}`
//! ([`Solver::recorded_position`] gives `x_n`).
//!
//! **Architecture invariant:** no files, no terminal, no case format: the
//! caller builds a [`Model`] and [`Loads`] and calls [`Solver::step`].
//! Results are identical bit for bit for any number of threads.
//!
//! # Example
//!
//! A free elastic block given a uniform velocity moves rigidly: no stress,
//! and the kinetic energy it started with.
//!
//! ```
//! use femdem_core::Vec3;
//! use femdem_material::{ElasticParams, Law};
//! use femdem_mesh::generate::{BoxSpec, generate_box};
//! use femdem_mesh::{Region, insert_joints};
//! use femdem_solver::{Loads, Model, RegionBehaviour, Solver, StepParams, Want, held_nodes, stable_time_step};
//!
//! let region = Region { name: "rock".into(), breakable: false };
//! let spec = BoxSpec { min: [0.0; 3], max: [0.01; 3], element_size: 0.005, jitter: 0.0, seed: 1, region };
//! let mesh = insert_joints(&generate_box(&spec)?)?;
//! let material = ElasticParams { young: 26e9, poisson: 0.2, density: 2340.0, viscosity: 0.0 }.validate()?;
//! let behaviour = [RegionBehaviour::Deformable { law: Law::NeoHookean, material, joints: None }];
//! let model = Model::new(&mesh, &behaviour, 1.0)?;
//! let loads = Loads::default();
//! let stable = stable_time_step(&model, &held_nodes(&model, &loads)?, 100);
//! let mut solver = Solver::new(model, loads, StepParams::new(0.9 * stable.critical)?)?;
//! solver.set_velocity(|_| Vec3::new(1.0, 0.0, 0.0));
//! let mut kinetic = 0.0;
//! for _ in 0..10 {
//!     kinetic = solver.step(Want { energy: true, stress: false }).energies.kinetic;
//! }
//! let mass: f64 = solver.model().mass.iter().sum();
//! assert!((kinetic / (0.5 * mass) - 1.0).abs() < 1e-12);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod clock;
pub mod contact;
mod device;
mod error;
pub mod forces;
mod guard;
mod ledger;
pub mod loads;
mod model;
pub mod select;
pub mod snapshot;
mod state;
mod step;
mod timestep;
mod widest;
pub use widest::{VectorPath, widest_name};

pub use clock::StageTimes;
pub use contact::{Activation, Contact, ContactEnergy, ContactModel, ContactSettings, NEGLIGIBLE, RAMP_STEPS};
pub use device::Residency;
pub use error::SolverError;
pub use femdem_gpu::{Gpu, GpuError, Part, Phase};
pub use forces::{Dissipation, ForceSums, Want, Workspace};
pub use guard::{CONTACT_ENERGY_TOLERANCE, Trouble};
pub use ledger::{ENERGY_TOLERANCE, FLOOR_STRAIN, Imbalance};
pub use loads::{Fixed, Loads, Ramp, SurfaceKind, SurfaceLoad, VelocityDrive};
pub use model::{Gather, Model, RegionBehaviour, TetMaterial};
pub use state::{Energies, Failure, State};
pub use step::{FailureCounts, Solver, StepParams, StepRecord, held_nodes};
pub use timestep::{StableStep, contact_omega, element_transit, stable_time_step};
