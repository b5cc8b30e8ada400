//! Gmsh MSH import (4.1 and 2.0–2.2, ASCII and binary) and export (4.1,
//! ASCII).
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
//! Binary files (`Mesh.Binary = 1`) are read as Gmsh writes them: in the
//! byte order of the machine that wrote them (the `int` 1 after the
//! `$MeshFormat` line says which), `size_t` values of the header's data
//! size (4 or 8 bytes; in MSH 2 the data size is a `double`'s, 8, and
//! there are no `size_t` values); they give the same mesh as the ASCII file of the
//! same mesh, save that the ASCII file rounds coordinates to the 16 digits
//! Gmsh prints. In a binary file, elements of a type that
//! [`element_type_name`] does not know cannot be skipped (their node count
//! is unknown) and are refused. Errors in a binary file name the byte
//! offset and the section ([`MeshError::MshBinary`](crate::MeshError::MshBinary)).
//! MSH 2 (versions 2.0 to 2.2, Gmsh's legacy format, still written by
//! many tools) is read too, ASCII and binary (`read/legacy.rs`): an
//! element's first tag is its physical group, so each physical volume is a
//! region and each physical surface a group as above, and a physical group
//! that `$PhysicalNames` names is kept even when it holds no element (MSH
//! 2 has no entities to say more; MSH 2.0's names, which give no
//! dimension, name groups of either kind but make none). An
//! element in several physical groups is written once per group in MSH 2:
//! a triangle so is in each group; a tet written twice is refused (one
//! region per tet), and so is a file whose named groups hold no element
//! (`Mesh.SaveAll = 1`). Other versions are refused with a message that names
//! the Gmsh option to change (`Mesh.MshFileVersion = 4.1`). Partitioned
//! MSH 4.1 meshes are not supported (MSH 2's partition tags are ignored).
//!
//! Reading is split by concept: `lex.rs` (the ASCII tokenizer: lines and
//! fields), `binary.rs` (the binary tokenizer: raw `int`, `size_t` and
//! `double` in the file's byte order), `source.rs` (the interface both give
//! the section parsers), `read.rs` (`$MeshFormat`, then the section
//! parsers, written once for both encodings; those of MSH 2 in
//! `read/legacy.rs`) and `read/assemble.rs` (the mesh from what was read).

mod binary;
mod lex;
mod read;
mod report;
mod source;
mod write;

pub use read::{read_msh, read_msh_report};
pub use report::{MshReport, element_type_dimension, element_type_name};
pub use write::write_msh;
