//! The static start of femdem: a linear-elastic implicit solve that puts a
//! jointed model into equilibrium under its loads at `t = 0`, so that an
//! explicit run ([`femdem_solver::Solver`]) can start from the loaded state
//! at rest instead of ramping the loads up dynamically.
//!
//! # What is solved
//!
//! `K u = f` on the free displacement components (`dofs.rs`), with
//!
//! - `K`: the small-strain linear elastic stiffness of every deformable tet
//!   (its material's `λ`, `μ` from `E`, `ν`) and the initial tangent of
//!   every intact joint — the slope `p0 / h` of the Eq. 11 branches at zero
//!   opening and slip, normal and shear alike, integrated at the joint's
//!   three Hammer points over its face (`stiffness.rs`, where the formulas
//!   are derived) — so the split nodes of the jointed mesh are tied as the
//!   explicit joints tie them at small displacement;
//! - held at zero: the nodes of rigid (platen) regions and every fixed or
//!   velocity-driven component (a drive's from the first step on: one with
//!   a later `start_time` is free);
//! - `f`: the surface loads at `t = 0` on the reference geometry and
//!   gravity on the physical mass (`loads.rs`); a static start holds the
//!   surface loads at their full value from `t = 0`
//!   ([`hold_surface_loads`]);
//! - free bodies (no held component to stop some rigid motion, like a cube
//!   under pressures on all faces): inertia relief, the rigid-body part of
//!   the load taken out as a rigid acceleration and the rigid part of `u`
//!   removed (`bodies.rs`);
//! - the solution is refined until `‖K u − f_b‖ / ‖f‖` is below a
//!   tolerance, which is checked and reported (`solve.rs`);
//! - then (by default) it is corrected to the explicit model's own
//!   equilibrium — the neo-Hookean tets, the joints' hardening parabola
//!   (softer than its initial tangent by `r/2` at `r = δ/δp`), the
//!   pressures on the deformed faces — by modified Newton iterations with
//!   the factorised initial tangent, accelerated by Anderson mixing
//!   (`correction.rs`, `anderson.rs`), so that the explicit run starts at
//!   rest; the loaded state must be elastic enough for that equilibrium to
//!   exist, else the solve fails with [`StaticError::ModelNotConverged`].
//!
//! # Code map
//!
//! - [`static_solve`] (`solve.rs`): the driver, [`StaticOptions`],
//!   [`StaticSolution`] (the displacement, the residual, sizes and times).
//! - `stiffness.rs`: [`tet_stiffness`], [`joint_stiffness`],
//!   [`joint_initial_stiffness`].
//! - `assembly.rs`: the global stiffness on the unknowns.
//! - `bodies.rs`: connected bodies, free rigid modes, inertia relief.
//! - `sparse.rs`, `system.rs`: the lower-triangle compressed-column
//!   matrix, faer's sparse Cholesky (`Par::Seq`) of `K` shifted on
//!   floating bodies, and the corrections it gives.
//! - `correction.rs`, `anderson.rs`: the explicit model's out-of-balance
//!   force and the accelerated fixed-point iteration on it.
//! - `dofs.rs`, `loads.rs`: the unknowns and the load vector.
//!
//! # Determinism
//!
//! Every stage is sequential (faer is built without its `rayon` feature
//! and called with `Par::Seq`) and sums in a fixed order, except the
//! correction's force evaluation, which is femdem-solver's force pass, the
//! same bit for bit for any thread count: so is the displacement.
//!
//! # Limits
//!
//! Contact is not linearised: tets that start in contact across
//! pre-existing fracture faces (faces without a joint) are refused
//! ([`StaticError::InitialContact`]). Joints are taken intact.
//!
//! **Architecture invariant:** no files, no terminal, no case format: a
//! [`femdem_solver::Model`] and [`femdem_solver::Loads`] in, a displacement
//! out.
//!
//! # Example
//!
//! A free jointed cube under equal pressure on all six faces is compressed
//! uniformly and nothing accelerates. The continuum's strain would be
//! `−p (1 − 2ν) / E`; the joints' compliance `h / p0` adds to it (on this
//! two-cell lattice, about a third more).
//!
//! ```
//! use femdem_core::Vec3;
//! use femdem_fracture::{Coupling, GfCalibration, JointParams};
//! use femdem_material::{ElasticParams, Law};
//! use femdem_mesh::generate::{BoxSpec, generate_box};
//! use femdem_mesh::{Region, insert_joints};
//! use femdem_solver::{Loads, Model, Ramp, RegionBehaviour, SurfaceKind, SurfaceLoad};
//! use femdem_static::{StaticOptions, static_solve};
//!
//! let region = Region { name: "cube".into(), breakable: true };
//! let spec = BoxSpec { min: [0.0; 3], max: [0.02; 3], element_size: 0.01, jitter: 0.0, seed: 1, region };
//! let mesh = generate_box(&spec)?;
//! let jointed = insert_joints(&mesh)?;
//! let material = ElasticParams { young: 30e9, poisson: 0.25, density: 2700.0, viscosity: 0.0 }.validate()?;
//! let joints = JointParams {
//!     penalty: 3e11,
//!     tensile_strength: 1e6,
//!     cohesion: 2e6,
//!     friction_angle: 0.5,
//!     gf_tension: 60.0,
//!     gf_shear: 60.0,
//!     calibration: GfCalibration::Paper,
//!     coupling: Coupling::default(),
//! }
//! .validate()?;
//! let behaviour = [RegionBehaviour::Deformable { law: Law::NeoHookean, material, joints: Some(joints) }];
//! let model = Model::new(&jointed, &behaviour, 1.0)?;
//! let mut loads = Loads::default();
//! for side in ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"] {
//!     let group = jointed.mesh.boundary_group(side).unwrap();
//!     let faces = group.faces.iter().map(|f| f.nodes(&jointed.mesh.tets)).collect();
//!     loads.surfaces.push(SurfaceLoad { name: side.into(), faces, kind: SurfaceKind::Pressure(1e6), ramp: Ramp::STEP });
//! }
//! let solution = static_solve(&model, &loads, &[], &StaticOptions::default())?;
//! assert_eq!(solution.free_bodies, 1);
//! assert!(solution.residual < 1e-10 && solution.unbalanced < 1e-12);
//! let corner = (0..model.num_nodes()).find(|&i| model.x0[i] == Vec3::repeat(0.02)).unwrap();
//! let strain = solution.displacement[corner].x / 0.01; // the centre stays put
//! let continuum = -1e6 * (1.0 - 2.0 * 0.25) / 30e9;
//! assert!(strain < continuum && strain > 1.5 * continuum, "{strain} vs {continuum}");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod anderson;
mod assembly;
mod bodies;
mod correction;
mod dofs;
mod error;
mod loads;
mod solve;
mod sparse;
mod stiffness;
mod system;

pub use correction::JointCount;
pub use error::StaticError;
pub use solve::{StaticOptions, StaticSolution, Timings, static_solve};
pub use stiffness::{joint_initial_stiffness, joint_stiffness, tet_stiffness};

use femdem_solver::{Loads, Ramp};

/// Makes every surface load act in full from `t = 0`: its ramp time is set
/// to zero (its stop time is kept). This is what a static start does with
/// the ramps of a case: the static solve finds the equilibrium under the
/// held loads, and the explicit run continues under them. Velocity drives
/// keep their ramps (their displacement at `t = 0` is zero either way);
/// gravity has no ramp.
pub fn hold_surface_loads(loads: &mut Loads) {
    for s in &mut loads.surfaces {
        s.ramp = Ramp { ramp_time: 0.0, stop_time: s.ramp.stop_time };
    }
}
