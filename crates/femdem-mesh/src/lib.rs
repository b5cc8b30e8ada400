//! Tetrahedral meshes for the combined finite–discrete element method.
//!
//! This crate owns the mesh of the reference paper (Guo, Xiang, Latham,
//! Izzuddin, §2.1 and Fig. 2): 4-node tetrahedra, generators that need no
//! external tool, Gmsh MSH import (4.1 and 2.2) and export (4.1), mesh checks and
//! statistics, and the insertion of 6-node cohesive joint elements on every
//! interior face of a breakable region. Its main entry point for another
//! solver is [`insert_joints`]: a jointed mesh from any tet mesh.
//!
//! # Code map
//!
//! - [`TetMesh`] (`mesh.rs`): the mesh as flat parallel arrays (`coords`,
//!   `tets`, `tet_region`), its [`Region`]s, named [`BoundaryGroup`]s and
//!   `fracture_faces`; faces are [`FaceRef`]s.
//! - [`faces`]: [`face_adjacency`], interior and boundary faces by a
//!   parallel sort of face keys.
//! - [`generate`]: the jittered Freudenthal box (`generate_box`), the
//!   constrained-Delaunay extrusion of a 2D outline with fracture traces
//!   (`generate_extrusion`), and rigid platens (`generate_platen`).
//! - [`msh`]: Gmsh MSH `read_msh` (4.1 and 2.0–2.2; ASCII and binary,
//!   either byte order) and `write_msh` (4.1, ASCII).
//! - [`check`](mod@check): what a mesh must satisfy to be simulated;
//!   [`stats`](mod@stats) ([`MeshStats`]): counts, edge lengths, quality,
//!   volumes per region.
//! - [`joints`]: [`insert_joints`] and [`JointedMesh`] — split nodes, the
//!   joints `N1…N6`, each node's `origin`, and the initial contacts of
//!   pre-existing fractures; [`insert_joints_within`] confines the joints
//!   of breakable regions to the tets of a mask (a joint zone), the rest
//!   keeping shared nodes.
//! - [`MeshError`] (`error.rs`): every failure of the above.
//!
//! # Conventions
//!
//! - Lengths in m. Node ids are `u32` indices into `coords`, tet ids `u32`
//!   indices into `tets`, region ids `u16` indices into `regions`.
//! - **Tets** are positively oriented as in [`femdem_core::tet`]
//!   (`(x₁ − x₀) · ((x₂ − x₀) × (x₃ − x₀)) > 0`); generators and
//!   [`msh::read_msh`] guarantee it and [`check::check`] verifies it.
//! - **Faces** are named by tet and local index, [`FaceRef`]`{ tet, local }`,
//!   face `local` being the face opposite local node `local`, with the
//!   outward node order of [`femdem_core::tet::FACES`]. Such names survive
//!   the renumbering of nodes by joint insertion.
//! - **Joints** follow Fig. 2 of the paper. A joint
//!   `[N1, N2, N3, N4, N5, N6]` lies on the face shared by tets `a < b`:
//!   `N1 N2 N3` are `a`'s nodes on it, counter-clockwise seen from outside
//!   `a`, so `(N2 − N1) × (N3 − N1)` points from `a` to `b`; `N4 N5 N6` are
//!   `b`'s nodes that start at the positions of `N3 N2 N1` (the pairs
//!   `N1–N6`, `N2–N5`, `N3–N4` coincide in the reference state), so they run
//!   counter-clockwise seen from outside `b`. This is the order
//!   `femdem_fracture::joint_update` expects.
//! - **Node origin.** Every node of a [`JointedMesh`] records the vertex of
//!   the input mesh it was split from; two tets "share a node" in the sense
//!   of the paper's Eq. 15 when they have nodes of the same origin.
//! - The same input (and seed) gives the same mesh bit for bit; the
//!   parallel passes (face adjacency, statistics) do not depend on the
//!   thread count.
//!
//! **Architecture invariant:** this crate knows mesh formats and nothing
//! else of files: no case files, no terminal, no physics.
//!
//! # Example
//!
//! A 2 × 1 × 1 cm box of 1 cm cells (12 tets), one breakable region: joint
//! insertion gives every tet its own four nodes and puts one joint on each
//! interior face, its node pairs `N1–N6`, `N2–N5`, `N3–N4` coincident.
//!
//! ```
//! use femdem_mesh::generate::{BoxSpec, generate_box};
//! use femdem_mesh::{Region, face_adjacency, insert_joints};
//!
//! let region = Region { name: "rock".into(), breakable: true };
//! let spec = BoxSpec { min: [0.0; 3], max: [0.02, 0.01, 0.01], element_size: 0.01, jitter: 0.1, seed: 7, region };
//! let mesh = generate_box(&spec)?;
//! femdem_mesh::check::check(&mesh)?;
//! assert_eq!(mesh.num_tets(), 2 * 6); // six Freudenthal tets per cell
//!
//! let jointed = insert_joints(&mesh)?;
//! assert_eq!(jointed.joints.len(), face_adjacency(&mesh)?.interior.len());
//! assert_eq!(jointed.mesh.num_nodes(), 4 * mesh.num_tets());
//! let x = &jointed.mesh.coords;
//! for j in &jointed.joints {
//!     for (p, q) in [(0, 5), (1, 4), (2, 3)] {
//!         assert_eq!(x[j[p] as usize], x[j[q] as usize]);
//!         assert_eq!(jointed.origin[j[p] as usize], jointed.origin[j[q] as usize]);
//!     }
//! }
//! # Ok::<(), femdem_mesh::MeshError>(())
//! ```

pub mod check;
mod error;
pub mod faces;
pub mod generate;
pub mod joints;
mod mesh;
pub mod msh;
pub mod order;
pub mod stats;
pub mod trace_file;

pub use error::MeshError;
pub use faces::{FaceAdjacency, face_adjacency};
pub use joints::{JointedMesh, insert_joints, insert_joints_within};
pub use mesh::{BoundaryGroup, FaceRef, Region, TetMesh};
pub use stats::{MeshStats, RegionStats, stats};
