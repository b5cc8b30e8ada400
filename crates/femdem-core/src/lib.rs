//! The bottom layer of femdem: the scalar type, small vector and matrix
//! aliases, and the geometry of one linear tetrahedron.
//!
//! # Code map
//!
//! - [`Real`], [`Vec3`], [`Mat3`], [`Vec2`] (this file): `f64` and the
//!   nalgebra stack types every other crate computes with.
//! - [`tet`] (`tet.rs`): one 4-node tet given its node positions —
//!   [`tet::signed_volume`], the outward face table [`tet::FACES`], the
//!   edge table [`tet::EDGES`], [`tet::triangle_area`],
//!   [`tet::surface_area`], [`tet::inradius`], [`tet::edge_lengths`],
//!   [`tet::aspect_ratio`] and [`tet::centroid`].
//! - [`lanes`] (`lanes.rs`): four `f64` lanes ([`lanes::F4`]) and lanes of
//!   3-vectors ([`lanes::F4x3`]) on plain arrays, for kernels that evaluate
//!   four elements at once and are compiled for the widest vector unit at
//!   run time.
//!
//! # Conventions
//!
//! - SI units: coordinates in m, areas in m², volumes in m³.
//! - **Orientation.** A tet `[x₀, x₁, x₂, x₃]` is positive when
//!   `V = (x₁ − x₀) · ((x₂ − x₀) × (x₃ − x₀)) / 6 > 0`, i.e. `x₃` lies on
//!   the side of the triangle `x₀ x₁ x₂` that its right-hand normal points
//!   to (the node order of VTK's `VTK_TETRA`). Every tet of a femdem mesh
//!   is positive in its reference state.
//! - **Faces.** Face `i` is the face opposite node `i`, ordered
//!   counter-clockwise seen from outside, so `(p₁ − p₀) × (p₂ − p₀)` is the
//!   outward normal (times twice the area) of a positive tet:
//!
//!   | face | opposite node | nodes ([`tet::FACES`]) |
//!   |---|---|---|
//!   | 0 | 0 | 1, 2, 3 |
//!   | 1 | 1 | 0, 3, 2 |
//!   | 2 | 2 | 0, 1, 3 |
//!   | 3 | 3 | 0, 2, 1 |
//!
//!   The crates above name a face by its tet and its index in this table,
//!   and orient joints and contact forces by it.
//!
//! **Architecture invariant:** this crate knows nothing of meshes,
//! materials, files or time stepping: everything here is a pure function of
//! coordinates, and every other femdem crate may depend on it.
//!
//! # Example
//!
//! The unit corner tet has volume 1/6, and each face normal of
//! [`tet::FACES`] points away from the centroid.
//!
//! ```
//! use femdem_core::Vec3;
//! use femdem_core::tet::{FACES, centroid, signed_volume, surface_area};
//!
//! let p = [Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()];
//! assert!((signed_volume(&p) - 1.0 / 6.0).abs() < 1e-15);
//! // Three right triangles of area ½ and an equilateral one of side √2.
//! assert!((surface_area(&p) - (1.5 + 3f64.sqrt() / 2.0)).abs() < 1e-15);
//!
//! let c = centroid(&p);
//! for [i, j, k] in FACES {
//!     let normal = (p[j] - p[i]).cross(&(p[k] - p[i]));
//!     assert!(normal.dot(&(p[i] - c)) > 0.0, "face {i} {j} {k} points outward");
//! }
//! // Swapping two nodes flips the orientation.
//! assert!(signed_volume(&[p[0], p[2], p[1], p[3]]) < 0.0);
//! ```

pub mod lanes;
pub mod tet;

/// The floating-point type of every physical quantity (SI units throughout).
pub type Real = f64;
/// A 3-vector of [`Real`].
pub type Vec3 = nalgebra::Vector3<Real>;
/// A 3×3 matrix of [`Real`].
pub type Mat3 = nalgebra::Matrix3<Real>;
/// A 2-vector of [`Real`], used by planar generators.
pub type Vec2 = nalgebra::Vector2<Real>;
