//! VTK output of femdem: one binary XML unstructured grid (`.vtu`) per
//! output step, a ParaView collection (`.pvd`) that lists the steps with
//! their times, and CSV run histories.
//!
//! * [`Frame`] and [`Field`] borrow what one step shows: point coordinates,
//!   4-node tets, and named arrays on points and cells (scalars, vectors,
//!   9-component tensors). [`Frame::validate`] checks every length.
//! * [`write_vtu`] writes one frame; [`SeriesWriter`] writes numbered frames
//!   and rewrites the `.pvd` after each, so an interrupted run stays
//!   viewable.
//! * [`HistoryWriter`] writes a CSV header and rows of round-trip-exact
//!   numbers.
//!
//! **Architecture invariant:** this is the only femdem crate that writes
//! VTK. It knows nothing of physics or case files: it writes the arrays it
//! is given under the names it is given, and never decides what to output.
//!
//! ```no_run
//! use femdem_vtk::{Field, Frame, HistoryWriter, SeriesWriter};
//! # fn main() -> Result<(), femdem_vtk::VtkError> {
//! let points = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
//! let tets = [[0, 1, 2, 3]];
//! let displacement = [[0.0; 3]; 4];
//! let stress = [[0.0; 9]];
//! let point_fields = [Field::vector("displacement", &displacement)];
//! let cell_fields = [Field::tensor("stress", &stress)];
//! let frame = Frame::new(&points, &tets)
//!     .with_point_fields(&point_fields)
//!     .with_cell_fields(&cell_fields);
//!
//! let mut series = SeriesWriter::new("out".as_ref(), "block")?;
//! series.write(0.0, &frame)?; // out/block_000000.vtu, out/block.pvd
//!
//! let mut history = HistoryWriter::create("out/history.csv".as_ref(), &["time", "energy"])?;
//! history.row(&[0.0, 0.0])?;
//! # Ok(())
//! # }
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
