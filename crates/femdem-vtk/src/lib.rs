//! VTK output of femdem: one binary XML unstructured grid (`.vtu`) per
//! output step, a ParaView collection (`.pvd`) that lists the steps with
//! their times, and CSV run histories.
//!
//! # Code map
//!
//! - [`Frame`] and [`Field`] (`frame.rs`) borrow what one step shows: point
//!   coordinates, 4-node tets (and optionally triangles, for fracture
//!   surfaces), and named arrays on points and cells (scalars, vectors,
//!   9-component tensors). [`Frame::validate`] checks every length before
//!   anything is written.
//! - [`write_vtu`] and [`write_vtu_with`] (`vtu.rs`, through vtkio) write
//!   one frame; [`VtuOptions`] choose the [`Compression`] (LZ4 by default).
//! - [`SeriesWriter`] (`series.rs`) writes numbered frames and rewrites the
//!   `.pvd` atomically after each, so an interrupted run stays viewable.
//! - [`HistoryWriter`] (`history.rs`) writes optional `#` comment lines, a
//!   CSV header and rows of round-trip-exact numbers.
//! - [`VtkError`] (`error.rs`): every failure, with the path concerned;
//!   `file.rs` holds the atomic file replacement and number formatting.
//!
//! # Conventions
//!
//! - Values are written as given, in the caller's units (femdem's are SI),
//!   as `Float64`: nothing is converted, scaled or renamed.
//! - Tets are `VTK_TETRA` cells with their node order unchanged. VTK
//!   expects the fourth node on the side to which the right-handed normal
//!   of the first three nodes points: the positive orientation of
//!   `femdem_core::tet`, so femdem's tets are passed as they are.
//! - Vectors have 3 components `x, y, z`; tensors all 9 components,
//!   row-major `xx, xy, xz, yx, …, zz` (see [`Field`]).
//! - Series times are finite and strictly increasing; CSV numbers parse
//!   back to the same `f64`.
//!
//! **Architecture invariant:** this is the only femdem crate that writes
//! VTK. It knows nothing of physics or case files (it does not even depend
//! on `femdem-core`): it writes the arrays it is given under the names it
//! is given, and never decides what to output.
//!
//! # Example
//!
//! One tet with a displacement and a stress field, written as step 0 of a
//! series, and a history row; the `.pvd` lists the step, and the CSV holds
//! the numbers exactly as given.
//!
//! ```
//! use femdem_vtk::{Field, Frame, HistoryWriter, SeriesWriter};
//!
//! let out = std::env::temp_dir().join(format!("femdem-vtk-doc-{}", std::process::id()));
//! let points = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
//! let tets = [[0, 1, 2, 3]];
//! let displacement = [[0.0, 0.0, 1e-6]; 4];
//! let stress = [[3e6, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]];
//! let point_fields = [Field::vector("displacement", &displacement)];
//! let cell_fields = [Field::tensor("stress", &stress)];
//! let frame = Frame::new(&points, &tets).with_point_fields(&point_fields).with_cell_fields(&cell_fields);
//! frame.validate()?;
//!
//! let mut series = SeriesWriter::new(&out, "block")?;
//! let vtu = series.write(0.0, &frame)?;
//! assert_eq!(vtu, out.join("block_000000.vtu"));
//! assert!(std::fs::read_to_string(series.pvd_path())?.contains("block_000000.vtu"));
//!
//! let mut history = HistoryWriter::create(&out.join("history.csv"), &["time", "energy"])?;
//! history.row(&[1e-7, 0.1])?;
//! history.flush()?;
//! assert_eq!(std::fs::read_to_string(out.join("history.csv"))?, "time,energy\n1e-7,0.1\n");
//! std::fs::remove_dir_all(&out)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod error;
mod file;
mod frame;
mod history;
mod series;
mod vtu;

pub use error::VtkError;
pub use frame::{Field, Frame, Location};
pub use history::HistoryWriter;
pub use series::SeriesWriter;
pub use vtu::{Compression, VtuOptions, write_vtu, write_vtu_with};
