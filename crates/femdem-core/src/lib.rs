//! The bottom layer of femdem: the scalar type, small vector and matrix
//! aliases, and the geometry of one linear tetrahedron.
//!
//! Everything here is a pure function of coordinates. **Architecture
//! invariant:** this crate knows nothing of meshes, materials, files or time
//! stepping; every other femdem crate may depend on it.

pub mod tet;

/// The floating-point type of every physical quantity (SI units throughout).
pub type Real = f64;
/// A 3-vector of [`Real`].
pub type Vec3 = nalgebra::Vector3<Real>;
/// A 3×3 matrix of [`Real`].
pub type Mat3 = nalgebra::Matrix3<Real>;
/// A 2-vector of [`Real`], used by planar generators.
pub type Vec2 = nalgebra::Vector2<Real>;
