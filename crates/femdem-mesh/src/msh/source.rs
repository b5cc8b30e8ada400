//! What the section parsers read from: the records of an MSH file as typed
//! values, whatever its encoding. The ASCII tokenizer ([`super::lex`])
//! and the binary one ([`super::binary`]) implement [`Source`]; the
//! parsers of `$Entities`, `$Nodes` and `$Elements` ([`super::read`]) are
//! written once against it.
//!
//! The value kinds follow the MSH 4.1 specification, which gives each
//! field a C type for binary files: [`Source::count`] and
//! [`Source::node_tag`] are `size_t` (of the header's data size),
//! [`Source::int`] and [`Source::uint`] are `int`, [`Source::real`] is
//! `double`. In an ASCII file they are whitespace-separated numbers, one
//! record per line. The MSH 2 parsers (`read/legacy.rs`) read their
//! binary values, all `int` and `double`, through [`Source::int`],
//! [`Source::uint`] and [`Source::real`] only; their section counts are
//! text lines in both encodings.

use super::lex::Lines;
use crate::MeshError;

/// Where in an MSH file: a line of an ASCII file (or of the text head of a
/// binary one), or a byte of a binary one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum At {
    /// 1-based line.
    Line(usize),
    /// 0-based byte offset.
    Byte(usize),
}

impl At {
    /// The error `message` here, in `section` (named by binary errors;
    /// ASCII errors have their line).
    pub(super) fn err(self, section: &str, message: impl Into<String>) -> MeshError {
        match self {
            At::Line(line) => MeshError::Msh { line, message: message.into() },
            At::Byte(offset) => MeshError::MshBinary { offset, section: section.to_owned(), message: message.into() },
        }
    }

    /// `"line 12"` or `"byte 3456"`, for messages that point at a second
    /// place.
    pub(super) fn describe(self) -> String {
        match self {
            At::Line(l) => format!("line {l}"),
            At::Byte(b) => format!("byte {b}"),
        }
    }
}

/// The records of the sections that Gmsh writes in binary in a binary
/// file (`$Entities`, `$Nodes`, `$Elements`), read value by value.
///
/// A record is what an ASCII file holds on one line. [`Source::record`]
/// starts one; the value readers take its fields in order; [`Source::end`]
/// checks that nothing is left of it (in binary, where records have no
/// end, it does nothing).
pub(super) trait Source<'a> {
    /// The text lines of the file: all of an ASCII file; the section
    /// headers, the `$End` lines and `$PhysicalNames` of a binary one.
    fn lines(&mut self) -> &mut Lines<'a>;

    /// Starts the next record of `section`. `what` says what was expected,
    /// for the error when the section or the file ends instead.
    fn record(&mut self, section: &'static str, what: impl FnOnce() -> String) -> Result<(), MeshError>;

    /// Where the current record starts.
    fn at(&self) -> At;

    /// The error `message` at the current record (ASCII: its line) or at
    /// the value last read (binary).
    fn err(&self, message: impl Into<String>) -> MeshError;

    /// A count or a size: `size_t`, a non-negative integer.
    fn count(&mut self, name: &str) -> Result<usize, MeshError>;

    /// A tag or a dimension: `int`, an integer.
    fn int(&mut self, name: &str) -> Result<i32, MeshError>;

    /// A flag or an element type: `int`, a non-negative integer.
    fn uint(&mut self, name: &str) -> Result<u32, MeshError>;

    /// A node or element tag: `size_t`, a positive integer.
    fn node_tag(&mut self, name: &str) -> Result<u64, MeshError>;

    /// A coordinate: `double`, finite.
    fn real(&mut self, name: &str) -> Result<f64, MeshError>;

    /// Checks that nothing is left of the record; `what` names its last
    /// field.
    fn end(&mut self, what: &str) -> Result<(), MeshError>;

    /// How many fields the current record has, where records are lines
    /// (ASCII); `None` in binary.
    fn fields(&self) -> Option<usize>;

    /// Reads past the node tags of an element of Gmsh type `ty` that is
    /// skipped (its element tag read), checking their number.
    fn skip_element_nodes(&mut self, ty: u32) -> Result<(), MeshError>;

    /// Where the next record starts, for an error about one that is
    /// missing (ASCII: the next line, which is read).
    fn next_at(&mut self, section: &'static str) -> Result<At, MeshError>;

    /// Expects the end of `section`: its `$End` line (in binary, after the
    /// line break that ends the data).
    fn end_of(&mut self, section: &'static str) -> Result<(), MeshError>;
}
