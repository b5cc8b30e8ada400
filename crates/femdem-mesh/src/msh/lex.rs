//! Line-oriented lexing of MSH text: numbered lines and the
//! whitespace-separated fields of one record, with errors that carry the
//! line number; and [`Ascii`], the [`Source`] of an ASCII file.
//!
//! A binary file has text too (its section headers, `$End` lines and
//! `$PhysicalNames`): its [`Lines`] count bytes instead ([`Lines::bytes_mode`]),
//! so that every error in it has a byte offset.

use std::str::SplitAsciiWhitespace;

use super::report::element_type_nodes;
use super::source::{At, Source};
use crate::MeshError;

/// Lines of the file, numbered from 1.
pub(super) struct Lines<'a> {
    rest: &'a [u8],
    /// Number of the line last returned (0 before the first).
    line: usize,
    /// Bytes before `rest`.
    offset: usize,
    /// Offset of the line last returned.
    line_start: usize,
    /// Whether places are byte offsets (a binary file) rather than lines.
    bytes: bool,
}

impl<'a> Lines<'a> {
    /// Lines of `bytes`, after a UTF-8 byte order mark if the file starts
    /// with one (an editor's, not Gmsh's): byte offsets still count it.
    pub(super) fn new(bytes: &'a [u8]) -> Self {
        const BOM: &[u8] = b"\xEF\xBB\xBF";
        let rest = bytes.strip_prefix(BOM).unwrap_or(bytes);
        let offset = bytes.len() - rest.len();
        Lines { rest, line: 0, offset, line_start: offset, bytes: false }
    }

    /// From here on, places are byte offsets: the file is binary.
    pub(super) fn bytes_mode(&mut self) {
        self.bytes = true;
        self.line_start = self.offset;
    }

    /// The line last returned (its first byte in bytes mode).
    pub(super) fn at(&self) -> At {
        if self.bytes { At::Byte(self.line_start) } else { At::Line(self.line.max(1)) }
    }

    /// Bytes read so far.
    pub(super) fn offset(&self) -> usize {
        self.offset
    }

    pub(super) fn err(&self, section: &str, message: impl Into<String>) -> MeshError {
        self.at().err(section, message)
    }

    /// The next `n` bytes, or `None` if fewer are left (binary data).
    pub(super) fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        if self.rest.len() < n {
            return None;
        }
        let (taken, rest) = self.rest.split_at(n);
        self.rest = rest;
        self.offset += n;
        Some(taken)
    }

    /// Bytes left.
    pub(super) fn left(&self) -> usize {
        self.rest.len()
    }

    /// Skips ASCII whitespace (between binary data and an `$End` line).
    pub(super) fn skip_whitespace(&mut self) {
        let n = self.rest.iter().take_while(|b| b.is_ascii_whitespace()).count();
        self.take(n);
    }

    /// The next line as bytes, without its line break.
    fn next_raw(&mut self) -> Option<&'a [u8]> {
        if self.rest.is_empty() {
            return None;
        }
        let len = self.rest.iter().position(|&b| b == b'\n').map_or(self.rest.len(), |i| i + 1);
        self.line_start = self.offset;
        let raw = self.take(len).unwrap_or_default();
        self.line += 1;
        let raw = raw.strip_suffix(b"\n").unwrap_or(raw);
        Some(raw.strip_suffix(b"\r").unwrap_or(raw))
    }

    /// The next line without its line break, or `None` at end of file;
    /// `section` is where it is read (for binary errors).
    pub(super) fn next_line(&mut self, section: &str) -> Result<Option<&'a str>, MeshError> {
        let Some(raw) = self.next_raw() else { return Ok(None) };
        std::str::from_utf8(raw).map(Some).map_err(|_| {
            if self.bytes {
                self.err(
                    section,
                    "binary data where a line of text was expected: do the counts that come before it match the data?",
                )
            } else {
                self.err(section, "not valid UTF-8 (binary data in an ASCII MSH file?)")
            }
        })
    }

    /// The next record of section `section`, trimmed. A section end (any
    /// line starting with `$`) or the end of file is an error that says
    /// `what` was expected.
    pub(super) fn record(
        &mut self,
        section: &'static str,
        what: impl FnOnce() -> String,
    ) -> Result<Fields<'a>, MeshError> {
        match self.next_line(section)? {
            None => Err(self.err(section, format!("file ends inside ${section}: expected {}", what()))),
            Some(l) if l.trim_start().starts_with('$') => {
                Err(self.err(section, format!("${section} ends early: expected {}, found `{}`", what(), l.trim())))
            }
            Some(l) => Ok(Fields { raw: l, it: l.split_ascii_whitespace(), at: self.at(), section }),
        }
    }

    /// Expects the line `$End<section>`.
    pub(super) fn end_of(&mut self, section: &str) -> Result<(), MeshError> {
        match self.next_line(section)? {
            Some(l) if l.trim() == format!("$End{section}") => Ok(()),
            Some(l) => Err(self.err(section, format!("expected $End{section}, found `{}`", l.trim()))),
            None => Err(self.err(section, format!("file ends inside ${section}: expected $End{section}"))),
        }
    }

    /// Skips an unknown section up to its line `$End<name>` (compared as
    /// bytes: the section may hold binary data). `start` is where its
    /// header is.
    pub(super) fn skip_section(&mut self, name: &str, start: At) -> Result<(), MeshError> {
        let end = format!("$End{name}");
        while let Some(l) = self.next_raw() {
            if l.trim_ascii() == end.as_bytes() {
                return Ok(());
            }
        }
        Err(start.err(name, format!("section ${name} is never closed by {end}")))
    }
}

/// The whitespace-separated fields of one record.
pub(super) struct Fields<'a> {
    /// The whole line.
    pub(super) raw: &'a str,
    pub(super) it: SplitAsciiWhitespace<'a>,
    /// Where the line is.
    pub(super) at: At,
    /// The section it is in.
    pub(super) section: &'static str,
}

impl<'a> Fields<'a> {
    /// An empty record, before the first one is read.
    fn none() -> Self {
        Fields { raw: "", it: "".split_ascii_whitespace(), at: At::Line(1), section: "" }
    }

    pub(super) fn err(&self, message: impl Into<String>) -> MeshError {
        self.at.err(self.section, message)
    }

    pub(super) fn token(&mut self, name: &str) -> Result<&'a str, MeshError> {
        let (at, section) = (self.at, self.section);
        self.it.next().ok_or_else(|| at.err(section, format!("missing {name}")))
    }

    pub(super) fn parse<T: std::str::FromStr>(&mut self, name: &str, kind: &str) -> Result<T, MeshError> {
        let tok = self.token(name)?;
        tok.parse().map_err(|_| self.err(format!("bad {name} `{tok}`: expected {kind}")))
    }

    pub(super) fn count(&mut self, name: &str) -> Result<usize, MeshError> {
        self.parse(name, "a non-negative integer")
    }

    pub(super) fn int(&mut self, name: &str) -> Result<i32, MeshError> {
        self.parse(name, "an integer")
    }

    pub(super) fn node_tag(&mut self, name: &str) -> Result<u64, MeshError> {
        let tag: u64 = self.parse(name, "a positive integer")?;
        if tag == 0 {
            return Err(self.err(format!("bad {name} `0`: tags start at 1")));
        }
        Ok(tag)
    }

    pub(super) fn real(&mut self, name: &str) -> Result<f64, MeshError> {
        let tok = self.token(name)?;
        match tok.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(self.err(format!("bad {name} `{tok}`: expected a finite number"))),
        }
    }

    /// Checks that no field is left.
    pub(super) fn end(&mut self, what: &str) -> Result<(), MeshError> {
        match self.it.next() {
            None => Ok(()),
            Some(tok) => Err(self.err(format!("unexpected `{tok}` after {what}"))),
        }
    }
}

/// An ASCII MSH file: one record per line.
pub(super) struct Ascii<'a> {
    lines: Lines<'a>,
    /// The record being read.
    current: Fields<'a>,
}

impl<'a> Ascii<'a> {
    pub(super) fn new(lines: Lines<'a>) -> Self {
        Ascii { lines, current: Fields::none() }
    }
}

impl<'a> Source<'a> for Ascii<'a> {
    fn lines(&mut self) -> &mut Lines<'a> {
        &mut self.lines
    }

    fn record(&mut self, section: &'static str, what: impl FnOnce() -> String) -> Result<(), MeshError> {
        self.current = self.lines.record(section, what)?;
        Ok(())
    }

    fn at(&self) -> At {
        self.current.at
    }

    fn err(&self, message: impl Into<String>) -> MeshError {
        self.current.err(message)
    }

    fn count(&mut self, name: &str) -> Result<usize, MeshError> {
        self.current.count(name)
    }

    fn int(&mut self, name: &str) -> Result<i32, MeshError> {
        self.current.int(name)
    }

    fn uint(&mut self, name: &str) -> Result<u32, MeshError> {
        self.current.parse(name, "a non-negative integer")
    }

    fn node_tag(&mut self, name: &str) -> Result<u64, MeshError> {
        self.current.node_tag(name)
    }

    fn real(&mut self, name: &str) -> Result<f64, MeshError> {
        self.current.real(name)
    }

    fn end(&mut self, what: &str) -> Result<(), MeshError> {
        self.current.end(what)
    }

    fn fields(&self) -> Option<usize> {
        Some(self.current.raw.split_ascii_whitespace().count())
    }

    fn skip_element_nodes(&mut self, ty: u32) -> Result<(), MeshError> {
        let nodes = self.current.it.by_ref().count();
        let ok = match element_type_nodes(ty) {
            Some(k) => nodes == k,
            None => nodes > 0,
        };
        if !ok {
            let k = element_type_nodes(ty).unwrap_or(0);
            return Err(self.err(format!("element of type {ty} has {nodes} node tags, expected {k}")));
        }
        Ok(())
    }

    fn next_at(&mut self, section: &'static str) -> Result<At, MeshError> {
        self.lines.next_line(section)?;
        Ok(self.lines.at())
    }

    fn end_of(&mut self, section: &'static str) -> Result<(), MeshError> {
        self.lines.end_of(section)
    }
}
