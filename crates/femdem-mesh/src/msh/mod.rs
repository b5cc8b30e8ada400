//! Gmsh MSH 4.1 import and export (ASCII only).
//!
//! [`read_msh`] turns a Gmsh mesh into a [`TetMesh`](crate::TetMesh):
//!
//! - each physical volume becomes a [`Region`](crate::Region) named after
//!   it (`"volume_<tag>"` when it has no name), in increasing tag order;
//!   tets of volume entities in no physical group go to a region called
//!   `"unnamed"`, placed last. Physical volumes with the same name share one
//!   region. Every region is read as breakable: MSH has no such notion, the
//!   case file says which regions may fracture.
//! - each physical surface becomes a [`BoundaryGroup`](crate::BoundaryGroup)
//!   (`"surface_<tag>"` when unnamed) whose 3-node triangles are matched to
//!   tet faces. A triangle on a face shared by two tets (an interior
//!   surface) is given to the tet whose outward face ordering agrees with
//!   the triangle's node order.
//! - tets in negative orientation are reoriented, and nodes that no tet
//!   uses (geometry points, nodes of skipped elements) are dropped, keeping
//!   the file order of the others.
//! - elements other than 4-node tets (type 4) and 3-node triangles (type 2)
//!   are skipped and counted in an [`MshReport`] ([`read_msh_report`]).
//!
//! [`write_msh`] writes the reverse: one volume entity and physical volume
//! per region, one surface entity and physical surface per boundary group.
//! `read_msh(write_msh(m))` gives back `m` up to the order of faces inside a
//! group, provided `m` uses all its nodes, has distinct region and group
//! names, and all its regions breakable: MSH stores neither the breakable
//! flag nor [`TetMesh::fracture_faces`](crate::TetMesh::fracture_faces).
//!
//! Binary MSH and versions other than 4.1 are refused with a message that
//! names the Gmsh option to change (`Mesh.Binary = 0`,
//! `Mesh.MshFileVersion = 4.1`). Partitioned meshes are not supported.

mod lex;
mod read;
mod report;
mod write;

pub use read::{read_msh, read_msh_report};
pub use report::{MshReport, element_type_name};
pub use write::write_msh;
