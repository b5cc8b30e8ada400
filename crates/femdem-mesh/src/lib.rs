//! Tetrahedral meshes for the combined finite–discrete element method.
//!
//! This crate owns the mesh of the reference paper (Guo, Xiang, Latham,
//! Izzuddin, §2.1 and Fig. 2): 4-node tetrahedra, generators that need no
//! external tool, Gmsh MSH 4.1 import and export, mesh checks and
//! statistics, and the insertion of 6-node cohesive joint elements on every
//! interior face of a breakable region.
//!
//! **Architecture invariant:** this crate knows mesh formats and nothing
//! else of files: no case files, no terminal, no physics.

pub mod check;
mod error;
pub mod faces;
pub mod generate;
pub mod joints;
mod mesh;
pub mod msh;
pub mod stats;

pub use error::MeshError;
pub use faces::{FaceAdjacency, face_adjacency};
pub use joints::{JointedMesh, insert_joints};
pub use mesh::{BoundaryGroup, FaceRef, Region, TetMesh};
pub use stats::{MeshStats, RegionStats, stats};
