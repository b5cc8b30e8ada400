//! Whole-file replacement and number formatting shared by the writers.

use std::fmt::Write as _;
use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

use crate::VtkError;

/// Buffer size for output files: large enough that multi-megabyte base64
/// blocks go to the kernel in few calls.
const BUFFER: usize = 1 << 20;

/// A buffered file writer that keeps the first I/O error.
///
/// vtkio's XML serialiser turns I/O errors into an opaque formatting error,
/// ignores short writes, and lets its inner `BufWriter` flush on drop, where
/// errors are lost. `Sink` writes every buffer whole (`write_all`), records
/// the first error for the caller to report with its path, and refuses all
/// writes after it.
pub(crate) struct Sink {
    inner: BufWriter<File>,
    error: Option<io::Error>,
}

impl Sink {
    /// Takes the first error seen, if any.
    pub(crate) fn take_error(&mut self) -> Option<io::Error> {
        self.error.take()
    }

    /// Records `e` (if it is the first) and returns a stand-in for it.
    fn fail(&mut self, e: io::Error) -> io::Error {
        let standin = io::Error::new(e.kind(), e.to_string());
        self.error.get_or_insert(e);
        standin
    }
}

impl Write for Sink {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        if self.error.is_some() {
            return Err(io::Error::other("an earlier write to this file failed"));
        }
        match self.inner.write_all(buf) {
            Ok(()) => Ok(buf.len()),
            Err(e) => Err(self.fail(e)),
        }
    }

    fn flush(&mut self) -> io::Result<()> {
        if self.error.is_some() {
            return Err(io::Error::other("an earlier write to this file failed"));
        }
        self.inner.flush().map_err(|e| self.fail(e))
    }
}

/// The temporary sibling that [`replace_file`] writes before renaming.
pub(crate) fn temp_path(path: &Path) -> PathBuf {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(".tmp");
    path.with_file_name(name)
}

/// Writes `path` through a temporary sibling that is renamed over it once
/// complete, so that readers (and an interrupted run) only ever see the old
/// file or the whole new one.
///
/// `body` writes the content into the [`Sink`]. The first I/O error the sink
/// met is reported (with the temporary file's path) in preference to
/// whatever `body` returned, so `body` may ignore write errors. On failure
/// the temporary file is removed and `path` is left untouched.
pub(crate) fn replace_file(path: &Path, body: impl FnOnce(&mut Sink) -> Result<(), VtkError>) -> Result<(), VtkError> {
    let tmp = temp_path(path);
    let file = File::create(&tmp).map_err(|e| VtkError::io(&tmp, e))?;
    let mut sink = Sink { inner: BufWriter::with_capacity(BUFFER, file), error: None };
    let result = body(&mut sink);
    // An I/O error met while writing explains any other failure of `body`.
    sink.flush().ok();
    let result = match sink.take_error() {
        Some(e) => Err(VtkError::io(&tmp, e)),
        None => result,
    };
    drop(sink);
    match result {
        Ok(()) => fs::rename(&tmp, path).map_err(|e| VtkError::io(path, e)),
        Err(e) => {
            // Best effort: the error being reported matters more.
            let _ = fs::remove_file(&tmp);
            Err(e)
        }
    }
}

/// Appends `x` with the fewest digits that parse back to the same `f64`:
/// plain notation for magnitudes in `[1e-5, 1e16)` and zero, scientific
/// otherwise (`1e-7`, `2.5e300`); `NaN`, `inf` and `-inf` as Rust spells
/// them (Python's `float()` and C's `strtod` read all of these).
pub(crate) fn push_f64(out: &mut String, x: f64) {
    let a = x.abs();
    // Writing to a String cannot fail.
    if a == 0.0 || !a.is_finite() || (1e-5..1e16).contains(&a) {
        let _ = write!(out, "{x}");
    } else {
        let _ = write!(out, "{x:e}");
    }
}

/// Appends `s` escaped for an XML attribute value in double quotes.
pub(crate) fn push_xml_attr(out: &mut String, s: &str) {
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn fmt(x: f64) -> String {
        let mut s = String::new();
        push_f64(&mut s, x);
        s
    }

    #[test]
    fn numbers_are_short_and_readable() {
        assert_eq!(fmt(0.0), "0");
        assert_eq!(fmt(-0.0), "-0");
        assert_eq!(fmt(0.1), "0.1");
        assert_eq!(fmt(1.5), "1.5");
        assert_eq!(fmt(1e-7), "1e-7");
        assert_eq!(fmt(-2.5e300), "-2.5e300");
        assert_eq!(fmt(1e16), "1e16");
        assert_eq!(fmt(f64::NAN), "NaN");
        assert_eq!(fmt(f64::NEG_INFINITY), "-inf");
    }

    proptest! {
        #[test]
        fn formatted_numbers_round_trip_exactly(bits in any::<u64>()) {
            let x = f64::from_bits(bits);
            let back: f64 = fmt(x).parse().unwrap();
            if x.is_nan() {
                prop_assert!(back.is_nan());
            } else {
                prop_assert_eq!(back.to_bits(), x.to_bits());
            }
        }
    }

    #[test]
    fn xml_attributes_are_escaped() {
        let mut s = String::new();
        push_xml_attr(&mut s, r#"a&b<c>"d'"#);
        assert_eq!(s, "a&amp;b&lt;c&gt;&quot;d&apos;");
    }

    #[test]
    fn failed_body_leaves_no_file_behind() {
        let dir = std::env::temp_dir().join(format!("femdem-vtk-file-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        let path = dir.join("x.txt");
        let err = replace_file(&path, |sink| {
            sink.write_all(b"partial").unwrap();
            Err(VtkError::RowLength { expected: 1, actual: 2 })
        })
        .unwrap_err();
        assert!(matches!(err, VtkError::RowLength { .. }));
        assert!(!path.exists());
        assert!(!temp_path(&path).exists());

        replace_file(&path, |sink| {
            sink.write_all(b"whole").unwrap();
            Ok(())
        })
        .unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap(), "whole");
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn missing_directory_error_names_the_file() {
        let path = Path::new("/nonexistent-femdem-dir/x.vtu");
        let err = replace_file(path, |_| Ok(())).unwrap_err();
        let msg = err.to_string();
        assert!(msg.contains("/nonexistent-femdem-dir/x.vtu.tmp"), "{msg}");
    }
}
