//! Line-oriented lexing of an ASCII MSH file: numbered lines and the
//! whitespace-separated fields of one record, with errors that carry the
//! line number.

use std::str::{FromStr, SplitAsciiWhitespace};

use crate::MeshError;

/// Lines of the file, numbered from 1.
pub(super) struct Lines<'a> {
    pub(super) rest: &'a [u8],
    /// Number of the line last returned (0 before the first).
    pub(super) line: usize,
}

impl<'a> Lines<'a> {
    pub(super) fn err(&self, message: impl Into<String>) -> MeshError {
        err_at(self.line.max(1), message)
    }

    /// The next line without its line break, or `None` at end of file.
    pub(super) fn next_line(&mut self) -> Result<Option<&'a str>, MeshError> {
        if self.rest.is_empty() {
            return Ok(None);
        }
        let (raw, rest) = match self.rest.iter().position(|&b| b == b'\n') {
            Some(i) => (&self.rest[..i], &self.rest[i + 1..]),
            None => (self.rest, &self.rest[self.rest.len()..]),
        };
        self.rest = rest;
        self.line += 1;
        let raw = raw.strip_suffix(b"\r").unwrap_or(raw);
        std::str::from_utf8(raw).map(Some).map_err(|_| self.err("not valid UTF-8 (binary data in an ASCII MSH file?)"))
    }

    /// The next record of section `section`, trimmed. A section end (any
    /// line starting with `$`) or the end of file is an error that says
    /// `what` was expected.
    pub(super) fn record(&mut self, section: &str, what: impl FnOnce() -> String) -> Result<Fields<'a>, MeshError> {
        match self.next_line()? {
            None => Err(self.err(format!("file ends inside ${section}: expected {}", what()))),
            Some(l) if l.trim_start().starts_with('$') => {
                Err(self.err(format!("${section} ends early: expected {}, found `{}`", what(), l.trim())))
            }
            Some(l) => Ok(Fields { raw: l, it: l.split_ascii_whitespace(), line: self.line }),
        }
    }

    /// Expects the line `$End<section>`.
    pub(super) fn end_of(&mut self, section: &str) -> Result<(), MeshError> {
        match self.next_line()? {
            Some(l) if l.trim() == format!("$End{section}") => Ok(()),
            Some(l) => Err(self.err(format!("expected $End{section}, found `{}`", l.trim()))),
            None => Err(self.err(format!("file ends inside ${section}: expected $End{section}"))),
        }
    }
}

pub(super) fn err_at(line: usize, message: impl Into<String>) -> MeshError {
    MeshError::Msh { line, message: message.into() }
}

/// The whitespace-separated fields of one record.
pub(super) struct Fields<'a> {
    /// The whole line.
    pub(super) raw: &'a str,
    pub(super) it: SplitAsciiWhitespace<'a>,
    pub(super) line: usize,
}

impl<'a> Fields<'a> {
    pub(super) fn err(&self, message: impl Into<String>) -> MeshError {
        err_at(self.line, message)
    }

    pub(super) fn token(&mut self, name: &str) -> Result<&'a str, MeshError> {
        let line = self.line;
        self.it.next().ok_or_else(|| err_at(line, format!("missing {name}")))
    }

    pub(super) fn parse<T: FromStr>(&mut self, name: &str, kind: &str) -> Result<T, MeshError> {
        let line = self.line;
        let tok = self.token(name)?;
        tok.parse().map_err(|_| err_at(line, format!("bad {name} `{tok}`: expected {kind}")))
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
        let line = self.line;
        let tok = self.token(name)?;
        match tok.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(err_at(line, format!("bad {name} `{tok}`: expected a finite number"))),
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
