//! Reading case files: parsing, with errors that name the file, the line,
//! the column and the key.

pub mod format;
#[cfg(test)]
mod fuzz;
pub mod mesh;
pub mod setup;
pub mod traces;
pub mod zones;

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

pub use format::{CASE_VERSION, Case};

/// An error located in a case file.
#[derive(Debug)]
pub struct CaseError {
    /// The case file.
    pub path: PathBuf,
    /// 1-based line and column, when known.
    pub at: Option<(usize, usize)>,
    /// The message, naming the key where there is one.
    pub message: String,
}

impl fmt::Display for CaseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.at {
            Some((l, c)) => write!(f, "{}:{l}:{c}: {}", self.path.display(), self.message),
            None => write!(f, "{}: {}", self.path.display(), self.message),
        }
    }
}

impl std::error::Error for CaseError {}

/// A parsed case with its source, for locating later errors.
pub struct LoadedCase {
    /// The case.
    pub case: Case,
    /// Where it was read from.
    pub path: PathBuf,
    /// Its text.
    pub source: String,
}

impl LoadedCase {
    /// An error at byte range `span` of the source.
    pub fn error_at(&self, span: Range<usize>, message: impl Into<String>) -> CaseError {
        CaseError { path: self.path.clone(), at: Some(line_col(&self.source, span.start)), message: message.into() }
    }

    /// The directory that relative paths in the case are taken from.
    pub fn dir(&self) -> &Path {
        self.path.parent().unwrap_or(Path::new("."))
    }
}

/// 1-based line and column (in characters) of byte `offset` of `text`.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// Where to point an error at. Serde reports an unknown key of a `kind`-
/// tagged table (the parts) at the table's header; the key's own line is
/// found by looking for `` `key` = `` at a line start between that header
/// and the next one.
fn key_offset(source: &str, span: Range<usize>, message: &str) -> usize {
    let key = message.strip_prefix("unknown field `").and_then(|m| m.split('`').next());
    let (Some(key), Some(text)) = (key, source.get(span.start..)) else {
        return span.start;
    };
    let mut offset = span.start;
    for (i, line) in text.split_inclusive('\n').enumerate() {
        let trimmed = line.trim_start();
        if i > 0 && trimmed.starts_with('[') {
            break;
        }
        if trimmed.strip_prefix(key).is_some_and(|rest| rest.trim_start().starts_with('=')) {
            return offset + (line.len() - trimmed.len());
        }
        offset += line.len();
    }
    span.start
}

/// Reads and parses `path`, checking the format version.
///
/// # Errors
/// A [`CaseError`] for an unreadable file, bad TOML, an unknown key, a
/// missing key, or an unsupported version.
pub fn load(path: &Path) -> Result<LoadedCase, CaseError> {
    let source = std::fs::read_to_string(path).map_err(|e| CaseError {
        path: path.to_path_buf(),
        at: None,
        message: format!("cannot read the case file: {e}"),
    })?;
    let case: Case = toml::from_str(&source).map_err(|e| CaseError {
        path: path.to_path_buf(),
        at: e.span().map(|s| line_col(&source, key_offset(&source, s, e.message()))),
        message: e.message().trim_end().to_string(),
    })?;
    let loaded = LoadedCase { case, path: path.to_path_buf(), source };
    if *loaded.case.version.get_ref() != CASE_VERSION {
        return Err(loaded.error_at(
            loaded.case.version.span(),
            format!("`version` is {}, but this femdem reads case format {CASE_VERSION}", loaded.case.version.get_ref()),
        ));
    }
    Ok(loaded)
}

#[cfg(test)]
mod tests {
    use super::line_col;

    #[test]
    fn line_col_counts_from_one() {
        let t = "a = 1\nbb = 2\n";
        assert_eq!(line_col(t, 0), (1, 1));
        assert_eq!(line_col(t, 6), (2, 1));
        assert_eq!(line_col(t, 8), (2, 3));
    }
}
