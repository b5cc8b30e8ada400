//! Constitutive laws of the femdem tetrahedra and the force kernel of one
//! 4-node tet.
//!
//! This crate owns §2.2, Eq. 1–2 of the reference paper (Guo, Xiang, Latham,
//! Izzuddin): the neo-Hookean viscoelastic Cauchy stress
//! `T = μ/J (B − I) + λ/J ln J I + η D` with `D = ½(L + Lᵀ)`, a
//! small-strain linear elastic law for verification, their strain energies,
//! and the nodal forces a stressed linear tet exerts on its nodes.
//!
//! # Code map
//!
//! - [`params`]: [`ElasticParams`] (what a user writes) validated into a
//!   [`Material`] (Lamé constants, P-wave modulus and speed), and
//!   [`critical_viscosity`], Munjiza's estimate used to choose `η`.
//! - [`law`]: [`Law`], [`cauchy_stress`] (Eq. 1–2), [`first_piola_kirchhoff`]
//!   and [`strain_energy_density`], including the documented behaviour of
//!   inverted elements (`J ≤` [`J_FLOOR`]).
//! - [`log1p`]: `ln(1 + x)` and `x − ln(1 + x)` without cancellation, for
//!   the energy at small strains.
//! - [`tet`]: the hot-path kernel: [`TetReference`] (`Dm⁻¹` and `V₀`),
//!   [`deformation_gradient`], [`velocity_gradient`], [`nodal_forces`] and
//!   [`tet_forces`], which returns forces, stress and stored energy of one
//!   tet in one call. No allocation; plain nalgebra stack types.
//! - [`tet_lanes`]: [`tet_forces_lanes`], the forces of four neo-Hookean
//!   tets at once in SIMD lanes, bit for bit those of [`tet_forces`].
//! - [`invariants`]: [`principal_stresses`] and [`von_mises`] for output.
//!
//! # Conventions
//!
//! - SI units: stresses and moduli in Pa, `η` in Pa·s, density in kg/m³,
//!   forces in N, energies in J.
//! - Stresses are Cauchy stresses (true stress), **tension positive**: a
//!   stretched element has `σ_xx > 0`.
//! - Tets follow the positive orientation of [`femdem_core::tet`]:
//!   `(X₁ − X₀) · ((X₂ − X₀) × (X₃ − X₀)) > 0` in the reference state.
//! - Forces are the forces the element exerts **on** its nodes: a solver
//!   adds them to the nodal force vector (they are `−f_int` of the paper's
//!   Eq. 19, `m v̇ + f_int = f_ext`).
//! - Inverted or crushed elements never produce NaN: below
//!   `J =` [`J_FLOOR`] the volumetric energy is continued linearly, so the
//!   forces stay finite, stay the exact gradient of the stored energy and
//!   push the element back towards positive volume (see [`law`]).
//!
//! **Architecture invariant:** this crate knows one tet and nothing more:
//! no meshes, no node numbering beyond the four local nodes, no time
//! stepping, no files or I/O of any kind. It depends on `femdem-core` only,
//! so another solver can use the laws and the kernel on their own.
//!
//! # Example
//!
//! The main entry point is [`tet_forces`]. Stretch the unit corner tet by
//! a small uniaxial strain `ε` (with the lateral contraction `−ν ε` of
//! uniaxial stress) and the neo-Hookean law gives Hooke's law,
//! `σ_xx = E ε` and no lateral stress, up to terms of order `ε²` (a
//! relative error of about `ε/3` here, checked to `ε`). The stretched tet
//! pulls its nodes together.
//!
//! ```
//! use femdem_core::{Mat3, Vec3};
//! use femdem_material::{ElasticParams, Law, TetReference, tet_forces};
//!
//! let (young, poisson) = (26e9, 0.2);
//! let material = ElasticParams { young, poisson, density: 2340.0, viscosity: 0.0 }.validate()?;
//! let x0 = [Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()];
//! let reference = TetReference::new(&x0).expect("a positive tet");
//! assert!((reference.volume - 1.0 / 6.0).abs() < 1e-16);
//!
//! let strain = 1e-5;
//! let f = Mat3::from_diagonal(&Vec3::new(1.0 + strain, 1.0 - poisson * strain, 1.0 - poisson * strain));
//! let x = x0.map(|p| f * p);
//! let at_rest = [Vec3::zeros(); 4];
//! let out = tet_forces(Law::NeoHookean, &material, &reference, &x, &at_rest);
//!
//! let hooke = young * strain;
//! assert!((out.stress[(0, 0)] / hooke - 1.0).abs() < strain);
//! assert!(out.stress[(1, 1)].abs() < strain * hooke && out.stress[(2, 2)].abs() < strain * hooke);
//! assert!(out.forces[1].x < 0.0 && out.forces[0].x > 0.0, "tension pulls the nodes together");
//! assert!(out.forces.iter().sum::<Vec3>().norm() < 1e-12 * out.forces[1].norm());
//! # Ok::<(), femdem_material::MaterialError>(())
//! ```

pub mod invariants;
pub mod law;
pub mod log1p;
pub mod params;
pub mod tet;
pub mod tet_lanes;

pub use invariants::{principal_stresses, von_mises};
pub use law::{J_FLOOR, Law, cauchy_stress, first_piola_kirchhoff, strain_energy_density};
pub use params::{ElasticParams, Material, MaterialError, critical_viscosity};
pub use tet::{TetReference, TetResult, deformation_gradient, nodal_forces, tet_forces, velocity_gradient};
pub use tet_lanes::{TET_LANES, tet_forces_lanes};
