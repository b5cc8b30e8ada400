//! Errors of the VTK output crate.

use std::path::PathBuf;

use thiserror::Error;

use crate::frame::Location;

/// Everything that can go wrong while writing VTU files, PVD collections or
/// CSV histories.
///
/// Invalid input (a [`Frame`](crate::Frame) whose arrays do not match, a
/// history row of the wrong length) is reported before anything is written.
#[derive(Debug, Error)]
pub enum VtkError {
    /// Reading or writing a file or directory failed.
    #[error("I/O error on {}: {source}", path.display())]
    Io {
        /// The file or directory concerned.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// Output of an earlier run cannot be continued (see
    /// `HistoryWriter::resume`, `SeriesWriter::resume`).
    #[error("cannot continue {}: {reason}", path.display())]
    Resume {
        /// The file concerned.
        path: PathBuf,
        /// Why.
        reason: String,
    },
    /// The VTK encoder (vtkio) failed to encode or serialise a frame.
    #[error("could not encode VTK file {}: {message}", path.display())]
    Encode {
        /// The file being written.
        path: PathBuf,
        /// The encoder's message.
        message: String,
    },
    /// A field's value count is not `components × count`.
    #[error(
        "{location} field `{name}`: {actual} values, expected {components} component(s) × \
         {count} {location}s = {expected}"
    )]
    FieldLength {
        /// Whether it is a point or a cell field.
        location: Location,
        /// The field name.
        name: String,
        /// Components per point or cell.
        components: usize,
        /// Number of points or cells in the frame.
        count: usize,
        /// `components × count`.
        expected: usize,
        /// Length of the value slice.
        actual: usize,
    },
    /// A field with zero components, or more than `u32::MAX`.
    #[error("{location} field `{name}` must have between 1 and 2^32 - 1 components")]
    BadComponents {
        /// Whether it is a point or a cell field.
        location: Location,
        /// The field name.
        name: String,
    },
    /// A field with an empty name.
    #[error("a {location} field has an empty name")]
    EmptyFieldName {
        /// Whether it is a point or a cell field.
        location: Location,
    },
    /// Two point fields, or two cell fields, with the same name.
    #[error("two {location} fields are named `{name}`")]
    DuplicateField {
        /// Whether they are point or cell fields.
        location: Location,
        /// The repeated name.
        name: String,
    },
    /// A tet refers to a point that does not exist.
    #[error("tet {tet} refers to point {node}, but the frame has {num_points} points")]
    NodeOutOfRange {
        /// Tet index.
        tet: usize,
        /// The bad point index.
        node: u32,
        /// Number of points in the frame.
        num_points: usize,
    },
    /// More points or cells than a VTU piece can count (`u32`).
    #[error("a VTU piece holds at most {max} {what}, got {count}")]
    TooLarge {
        /// `"points"` or `"cells"`.
        what: &'static str,
        /// The number given.
        count: usize,
        /// The limit.
        max: usize,
    },
    /// A series stem that is empty or is not a plain file name.
    #[error("invalid series stem {stem:?}: {reason}")]
    InvalidStem {
        /// The stem given.
        stem: String,
        /// Why it was rejected.
        reason: &'static str,
    },
    /// A series time that is NaN or infinite, or not after the previous one.
    #[error("series time {time:e} must be finite and later than the previous step's ({previous:?})")]
    BadTime {
        /// The time given.
        time: f64,
        /// The time of the previous step, if any.
        previous: Option<f64>,
    },
    /// A history with no columns, or a column name that is empty or holds a
    /// line break.
    #[error("invalid history column {name:?}: {reason}")]
    InvalidColumn {
        /// The column name given.
        name: String,
        /// Why it was rejected.
        reason: &'static str,
    },
    /// A history comment line that holds a line break.
    #[error("invalid history comment {text:?}: it holds a line break")]
    InvalidComment {
        /// The comment given.
        text: String,
    },
    /// A history row whose length differs from the number of columns.
    #[error("history row has {actual} values, but there are {expected} columns")]
    RowLength {
        /// Number of columns.
        expected: usize,
        /// Length of the row given.
        actual: usize,
    },
}

impl VtkError {
    /// Wraps an I/O error with the path it concerns.
    pub(crate) fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        VtkError::Io { path: path.into(), source }
    }
}
