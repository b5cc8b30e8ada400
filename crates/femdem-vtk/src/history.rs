//! Run histories (energies, loads, counts per step) as CSV.

use std::fs::{self, File};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use crate::VtkError;
use crate::file::push_f64;

/// A CSV file with a header line and one row of numbers per call to
/// [`row`](HistoryWriter::row).
///
/// Every value is written with the fewest digits that parse back to the
/// same `f64` (`0.1`, `1e-7`, `-2.5e300`, `NaN`, `inf`), so a reader such as
/// Rust's `str::parse`, Python's `float` or pandas recovers it bit for bit.
/// Output is buffered: call [`flush`](HistoryWriter::flush) at the points
/// where a reader should see the rows so far (the writer also flushes when
/// dropped, ignoring errors there).
#[derive(Debug)]
pub struct HistoryWriter {
    path: PathBuf,
    out: BufWriter<File>,
    columns: usize,
    line: String,
}

impl HistoryWriter {
    /// Creates (or truncates) `path`, creating its parent directories, and
    /// writes the header line.
    ///
    /// There must be at least one column; names must be non-empty and hold
    /// no line break. Names with a comma or a double quote are quoted as in
    /// RFC 4180.
    pub fn create(path: &Path, columns: &[&str]) -> Result<Self, VtkError> {
        if columns.is_empty() {
            return Err(VtkError::InvalidColumn { name: String::new(), reason: "a history needs at least one column" });
        }
        let mut header = String::new();
        for (i, &name) in columns.iter().enumerate() {
            let reason = if name.is_empty() {
                Some("empty")
            } else if name.contains(['\n', '\r']) {
                Some("contains a line break")
            } else {
                None
            };
            if let Some(reason) = reason {
                return Err(VtkError::InvalidColumn { name: name.to_owned(), reason });
            }
            if i > 0 {
                header.push(',');
            }
            if name.contains([',', '"']) || name.trim() != name {
                header.push('"');
                header.push_str(&name.replace('"', "\"\""));
                header.push('"');
            } else {
                header.push_str(name);
            }
        }
        header.push('\n');

        if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
            fs::create_dir_all(parent).map_err(|e| VtkError::io(parent, e))?;
        }
        let file = File::create(path).map_err(|e| VtkError::io(path, e))?;
        let mut writer = HistoryWriter {
            path: path.to_owned(),
            out: BufWriter::new(file),
            columns: columns.len(),
            line: String::with_capacity(32 * columns.len()),
        };
        writer.write_line(&header)?;
        Ok(writer)
    }

    /// Appends one row; `values` must have one value per column.
    pub fn row(&mut self, values: &[f64]) -> Result<(), VtkError> {
        if values.len() != self.columns {
            return Err(VtkError::RowLength { expected: self.columns, actual: values.len() });
        }
        let mut line = std::mem::take(&mut self.line);
        line.clear();
        for (i, &x) in values.iter().enumerate() {
            if i > 0 {
                line.push(',');
            }
            push_f64(&mut line, x);
        }
        line.push('\n');
        let result = self.write_line(&line);
        self.line = line;
        result
    }

    /// Writes the buffered rows to the file.
    pub fn flush(&mut self) -> Result<(), VtkError> {
        self.out.flush().map_err(|e| VtkError::io(&self.path, e))
    }

    /// The file written.
    pub fn path(&self) -> &Path {
        &self.path
    }

    fn write_line(&mut self, line: &str) -> Result<(), VtkError> {
        self.out.write_all(line.as_bytes()).map_err(|e| VtkError::io(&self.path, e))
    }
}

impl Drop for HistoryWriter {
    fn drop(&mut self) {
        // Errors cannot be reported from drop; call `flush` to see them.
        let _ = self.out.flush();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh directory per test (they run in parallel), and a file in it.
    fn temp_path(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("femdem-vtk-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        dir.join(name)
    }

    fn clean(path: &Path) {
        fs::remove_dir_all(path.parent().unwrap()).unwrap();
    }

    /// Parses a CSV written by `HistoryWriter` (unquoted fields only).
    fn parse(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
        let mut lines = text.lines();
        let header = lines.next().unwrap().split(',').map(str::to_owned).collect();
        let rows = lines.map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect();
        (header, rows)
    }

    #[test]
    fn rows_round_trip_bit_for_bit() {
        let path = temp_path("round_trip.csv");
        let rows = [
            vec![0.0, 1.0, -0.0],
            vec![0.1 + 0.2, 1.0 / 3.0, -2.5e300],
            vec![5e-324, f64::MAX, 1e-7],
            vec![f64::INFINITY, f64::NEG_INFINITY, 123_456_789.125],
        ];
        {
            let mut h = HistoryWriter::create(&path, &["time", "kinetic", "work"]).unwrap();
            for r in &rows {
                h.row(r).unwrap();
            }
            // Dropping flushes.
        }
        let text = fs::read_to_string(&path).unwrap();
        let (header, back) = parse(&text);
        assert_eq!(header, ["time", "kinetic", "work"]);
        assert_eq!(back.len(), rows.len());
        for (a, b) in rows.iter().zip(&back) {
            let a: Vec<u64> = a.iter().map(|x| x.to_bits()).collect();
            let b: Vec<u64> = b.iter().map(|x| x.to_bits()).collect();
            assert_eq!(a, b, "{text}");
        }
        assert!(text.contains("1e-7"), "{text}");
        clean(&path);
    }

    #[test]
    fn nan_is_written_and_read_back() {
        let path = temp_path("nan.csv");
        let mut h = HistoryWriter::create(&path, &["x"]).unwrap();
        h.row(&[f64::NAN]).unwrap();
        h.flush().unwrap();
        let (_, rows) = parse(&fs::read_to_string(&path).unwrap());
        assert!(rows[0][0].is_nan());
        clean(&path);
    }

    #[test]
    fn flush_makes_rows_visible() {
        let path = temp_path("flush.csv");
        let mut h = HistoryWriter::create(&path, &["a", "b"]).unwrap();
        h.row(&[1.0, 2.0]).unwrap();
        h.flush().unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap(), "a,b\n1,2\n");
        assert_eq!(h.path(), path);
        drop(h);
        clean(&path);
    }

    #[test]
    fn wrong_row_length_is_an_error_and_writes_nothing() {
        let path = temp_path("wrong_len.csv");
        let mut h = HistoryWriter::create(&path, &["a", "b"]).unwrap();
        let err = h.row(&[1.0]).unwrap_err();
        assert!(matches!(err, VtkError::RowLength { expected: 2, actual: 1 }), "{err}");
        h.flush().unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap(), "a,b\n");
        drop(h);
        clean(&path);
    }

    #[test]
    fn awkward_column_names_are_quoted_or_rejected() {
        let path = temp_path("names.csv");
        let h = HistoryWriter::create(&path, &["plain", "a,b", "say \"hi\""]).unwrap();
        drop(h);
        assert_eq!(fs::read_to_string(&path).unwrap(), "plain,\"a,b\",\"say \"\"hi\"\"\"\n");
        for bad in [&[][..], &[""][..], &["a\nb"][..]] {
            let err = HistoryWriter::create(&path, bad).unwrap_err();
            assert!(matches!(err, VtkError::InvalidColumn { .. }), "{err}");
        }
        clean(&path);
    }

    #[test]
    fn unwritable_path_error_names_it() {
        let err = HistoryWriter::create(Path::new("/proc/femdem/h.csv"), &["a"]).unwrap_err();
        assert!(err.to_string().contains("/proc/femdem"), "{err}");
    }
}
