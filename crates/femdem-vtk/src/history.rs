//! Run histories (energies, loads, counts per step) as CSV.

use std::fs::{self, File, OpenOptions};
use std::io::{BufRead, BufReader, BufWriter, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use crate::VtkError;
use crate::file::push_f64;

/// A CSV file with a header line and one row of numbers per call to
/// [`row`](HistoryWriter::row), optionally after comment lines that start
/// with `#` (what the file is: see
/// [`create_with_comments`](HistoryWriter::create_with_comments)).
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
    /// Bytes written so far (header included).
    written: u64,
}

impl HistoryWriter {
    /// Creates (or truncates) `path`, creating its parent directories, and
    /// writes the header line.
    ///
    /// There must be at least one column; names must be non-empty and hold
    /// no line break. Names with a comma or a double quote, or starting
    /// with `#`, are quoted as in RFC 4180 (so that the header never reads
    /// as a comment).
    pub fn create(path: &Path, columns: &[&str]) -> Result<Self, VtkError> {
        HistoryWriter::create_with_comments(path, &[], columns)
    }

    /// [`create`](HistoryWriter::create), with a line `# {comment}` per
    /// comment before the header: what the file is (a case, a title).
    /// Readers skip them as comments (pandas `read_csv(comment="#")`, R
    /// `read.csv(comment.char = "#")`); those that take the first line for
    /// the header (Python's `csv`) need them dropped first.
    ///
    /// # Errors
    /// [`VtkError::InvalidComment`] for a comment holding a line break, and
    /// the errors of [`create`](HistoryWriter::create).
    pub fn create_with_comments(path: &Path, comments: &[&str], columns: &[&str]) -> Result<Self, VtkError> {
        let header = header_line(columns)?;
        if let Some(c) = comments.iter().find(|c| c.contains(['\n', '\r'])) {
            return Err(VtkError::InvalidComment { text: (*c).to_owned() });
        }
        if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
            fs::create_dir_all(parent).map_err(|e| VtkError::io(parent, e))?;
        }
        let file = File::create(path).map_err(|e| VtkError::io(path, e))?;
        let mut writer = HistoryWriter {
            path: path.to_owned(),
            out: BufWriter::new(file),
            columns: columns.len(),
            line: String::with_capacity(32 * columns.len()),
            written: 0,
        };
        for c in comments {
            writer.write_line(&format!("# {c}\n"))?;
        }
        writer.write_line(&header)?;
        Ok(writer)
    }

    /// Reopens a history that an earlier writer of the same `columns` wrote
    /// to `path`, cut back to its first `len` bytes (a
    /// [`len`](HistoryWriter::len) taken then), to append rows after them:
    /// the rows written after that point are dropped. The comment lines
    /// the file starts with are kept as they are.
    ///
    /// # Errors
    /// [`VtkError::Resume`] if the file is shorter than `len` or its header
    /// (after its comment lines) is not that of `columns`;
    /// [`VtkError::Io`] if it cannot be opened or cut.
    pub fn resume(path: &Path, columns: &[&str], len: u64) -> Result<Self, VtkError> {
        let header = header_line(columns)?;
        let resume_error = |reason: String| VtkError::Resume { path: path.to_owned(), reason };
        let mut file = OpenOptions::new().read(true).write(true).open(path).map_err(|e| VtkError::io(path, e))?;
        let on_disk = file.metadata().map_err(|e| VtkError::io(path, e))?.len();
        if on_disk < len {
            return Err(resume_error(format!("{on_disk} bytes on disk, {len} expected")));
        }
        // The comment lines, then the header: read no further than `len`.
        let mut start = BufReader::new((&file).take(len));
        let mut comments = 0u64;
        let mut line = Vec::new();
        loop {
            line.clear();
            let n = start.read_until(b'\n', &mut line).map_err(|e| VtkError::io(path, e))?;
            if !line.starts_with(b"#") || !line.ends_with(b"\n") {
                break;
            }
            comments += n as u64;
        }
        if len < comments + header.len() as u64 {
            return Err(resume_error(format!("{len} bytes is shorter than the header")));
        }
        if line != header.as_bytes() {
            return Err(resume_error("its header is not that of this run's columns".into()));
        }
        drop(start);
        file.set_len(len).map_err(|e| VtkError::io(path, e))?;
        file.seek(SeekFrom::Start(len)).map_err(|e| VtkError::io(path, e))?;
        Ok(HistoryWriter {
            path: path.to_owned(),
            out: BufWriter::new(file),
            columns: columns.len(),
            line: String::with_capacity(32 * columns.len()),
            written: len,
        })
    }

    /// Bytes written so far, header included (buffered ones too: after
    /// [`flush`](HistoryWriter::flush) the file has this length).
    pub fn len(&self) -> u64 {
        self.written
    }

    /// Whether nothing has been written, not even the header (never true
    /// for a writer made by [`create`](HistoryWriter::create)).
    pub fn is_empty(&self) -> bool {
        self.written == 0
    }

    /// Flushes the buffered rows and asks the operating system to put the
    /// file's data on disk (`fsync`), so that [`len`](HistoryWriter::len)
    /// bytes survive a crash.
    pub fn sync(&mut self) -> Result<(), VtkError> {
        self.flush()?;
        self.out.get_ref().sync_data().map_err(|e| VtkError::io(&self.path, e))
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
        self.out.write_all(line.as_bytes()).map_err(|e| VtkError::io(&self.path, e))?;
        self.written += line.len() as u64;
        Ok(())
    }
}

/// The header line of `columns`, checked (see [`HistoryWriter::create`]).
fn header_line(columns: &[&str]) -> Result<String, VtkError> {
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
        if name.contains([',', '"']) || name.trim() != name || name.starts_with('#') {
            header.push('"');
            header.push_str(&name.replace('"', "\"\""));
            header.push('"');
        } else {
            header.push_str(name);
        }
    }
    header.push('\n');
    Ok(header)
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
    fn a_resumed_history_drops_the_rows_after_its_length_and_continues() {
        let path = temp_path("resume.csv");
        let columns = ["time", "x"];
        let mut h = HistoryWriter::create(&path, &columns).unwrap();
        h.row(&[0.0, 1.0]).unwrap();
        let at = h.len();
        h.row(&[1.0, 2.0]).unwrap();
        h.sync().unwrap();
        drop(h);
        let mut h = HistoryWriter::resume(&path, &columns, at).unwrap();
        assert_eq!(h.len(), at);
        h.row(&[1.5, 3.0]).unwrap();
        h.flush().unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap(), "time,x\n0,1\n1.5,3\n");
        assert_eq!(h.len(), fs::metadata(&path).unwrap().len());
        drop(h);
        for (cols, len) in [(&["time", "y"][..], at), (&columns[..], 1000), (&columns[..], 3)] {
            let err = HistoryWriter::resume(&path, cols, len).unwrap_err();
            assert!(matches!(err, VtkError::Resume { .. }), "{err}");
            assert!(err.to_string().contains("resume.csv"), "{err}");
        }
        clean(&path);
    }

    #[test]
    fn comment_lines_come_before_the_header_and_a_resume_keeps_them() {
        let path = temp_path("comments.csv");
        let columns = ["time", "#x"];
        let mut h = HistoryWriter::create_with_comments(&path, &["case: bar.toml", "title: a bar"], &columns).unwrap();
        h.row(&[0.0, 1.0]).unwrap();
        let at = h.len();
        h.row(&[1.0, 2.0]).unwrap();
        h.sync().unwrap();
        drop(h);
        let text = fs::read_to_string(&path).unwrap();
        assert_eq!(text, "# case: bar.toml\n# title: a bar\ntime,\"#x\"\n0,1\n1,2\n");
        let mut h = HistoryWriter::resume(&path, &columns, at).unwrap();
        h.row(&[1.5, 3.0]).unwrap();
        h.flush().unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap(), "# case: bar.toml\n# title: a bar\ntime,\"#x\"\n0,1\n1.5,3\n");
        drop(h);
        // Cut inside the comments or the header: refused.
        for len in [5, 35] {
            let err = HistoryWriter::resume(&path, &columns, len).unwrap_err();
            assert!(err.to_string().contains("shorter than the header"), "{len}: {err}");
        }
        let err = HistoryWriter::create_with_comments(&path, &["two\nlines"], &columns).unwrap_err();
        assert!(matches!(err, VtkError::InvalidComment { .. }), "{err}");
        clean(&path);
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
