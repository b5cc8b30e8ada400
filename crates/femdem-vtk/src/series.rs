//! A time series of `.vtu` files and the ParaView collection (`.pvd`) that
//! lists them.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

use crate::file::{push_f64, push_xml_attr, replace_file};
use crate::vtu::{VtuOptions, write_vtu_with};
use crate::{Frame, VtkError};

/// Writes the steps of one run as `{dir}/{stem}_{index:06}.vtu` and keeps
/// `{dir}/{stem}.pvd` listing every step written so far.
///
/// The `.pvd` file is rewritten (atomically: temporary file, then rename)
/// after every step, so that an interrupted run leaves a collection that
/// ParaView opens with all completed steps. It refers to the `.vtu` files by
/// name relative to `dir`, so the directory can be moved as a whole.
///
/// A new writer starts again at index 0 and overwrites the files of an
/// earlier run with the same stem step by step; stale files with higher
/// indices stay on disk but are not listed.
#[derive(Debug)]
pub struct SeriesWriter {
    dir: PathBuf,
    stem: String,
    options: VtuOptions,
    /// `(time, file name)` of every step written.
    steps: Vec<(f64, String)>,
}

impl SeriesWriter {
    /// A writer for `{dir}/{stem}_*.vtu` and `{dir}/{stem}.pvd`, creating
    /// `dir` (and its parents) if needed.
    ///
    /// `stem` must be a plain, non-empty file name: no `/` or `\`, no NUL,
    /// not `.` or `..`.
    pub fn new(dir: &Path, stem: &str) -> Result<Self, VtkError> {
        check_stem(stem)?;
        fs::create_dir_all(dir).map_err(|e| VtkError::io(dir, e))?;
        Ok(SeriesWriter {
            dir: dir.to_owned(),
            stem: stem.to_owned(),
            options: VtuOptions::default(),
            steps: Vec::new(),
        })
    }

    /// A writer that continues a series an earlier writer of `dir` and
    /// `stem` wrote, after its first `times.len()` steps (at `times`, as
    /// [`times`](SeriesWriter::times) gave them then): the `.pvd` is
    /// rewritten at once to list those steps only, and the next step
    /// written gets the index `times.len()` (later `.vtu` files of the
    /// earlier run are overwritten as the series reaches them).
    ///
    /// # Errors
    /// [`VtkError::Resume`] if a `.vtu` file of those steps is missing or
    /// the times do not increase; [`VtkError::Io`] if the `.pvd` cannot be
    /// written.
    pub fn resume(dir: &Path, stem: &str, times: &[f64]) -> Result<Self, VtkError> {
        let mut writer = SeriesWriter::new(dir, stem)?;
        for (k, &time) in times.iter().enumerate() {
            let name = format!("{stem}_{k:06}.vtu");
            let path = dir.join(&name);
            if !path.is_file() {
                return Err(VtkError::Resume { path, reason: "the frame is missing".into() });
            }
            if !time.is_finite() || writer.steps.last().is_some_and(|&(t, _)| time <= t) {
                return Err(VtkError::Resume { path, reason: format!("its time {time} does not follow the last") });
            }
            writer.steps.push((time, name));
        }
        writer.write_pvd()?;
        Ok(writer)
    }

    /// The times of the steps written so far, in order.
    pub fn times(&self) -> Vec<f64> {
        self.steps.iter().map(|&(t, _)| t).collect()
    }

    /// The same writer with these `.vtu` options (default: LZ4 compression).
    pub fn with_options(self, options: VtuOptions) -> Self {
        SeriesWriter { options, ..self }
    }

    /// Writes `frame` as the next step, at `time`, then rewrites the `.pvd`
    /// file. Returns the path of the `.vtu` file written.
    ///
    /// `time` must be finite and strictly greater than the previous step's
    /// (ParaView merges steps with equal times). On any error the `.pvd`
    /// file is left as it was and the step is not counted.
    pub fn write(&mut self, time: f64, frame: &Frame<'_>) -> Result<PathBuf, VtkError> {
        let previous = self.steps.last().map(|&(t, _)| t);
        if !time.is_finite() || previous.is_some_and(|p| time <= p) {
            return Err(VtkError::BadTime { time, previous });
        }
        let name = format!("{}_{:06}.vtu", self.stem, self.steps.len());
        let path = self.dir.join(&name);
        write_vtu_with(&path, frame, self.options)?;
        self.steps.push((time, name));
        if let Err(e) = self.write_pvd() {
            self.steps.pop();
            return Err(e);
        }
        Ok(path)
    }

    /// The path of the `.pvd` collection file.
    pub fn pvd_path(&self) -> PathBuf {
        self.dir.join(format!("{}.pvd", self.stem))
    }

    /// The directory the series is written to.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Number of steps written so far.
    pub fn len(&self) -> usize {
        self.steps.len()
    }

    /// Whether no step has been written yet.
    pub fn is_empty(&self) -> bool {
        self.steps.is_empty()
    }

    /// Replaces the `.pvd` file with one listing every step.
    fn write_pvd(&self) -> Result<(), VtkError> {
        let text = pvd_text(&self.steps);
        // A failed write is recorded by the sink and reported by
        // `replace_file`.
        replace_file(&self.pvd_path(), |sink| {
            let _ = sink.write_all(text.as_bytes());
            Ok(())
        })
    }
}

/// The text of a ParaView collection listing `steps`.
fn pvd_text(steps: &[(f64, String)]) -> String {
    let mut s = String::with_capacity(200 + 80 * steps.len());
    s.push_str("<?xml version=\"1.0\"?>\n");
    s.push_str("<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n");
    s.push_str("  <Collection>\n");
    for (time, file) in steps {
        s.push_str("    <DataSet timestep=\"");
        push_f64(&mut s, *time);
        s.push_str("\" group=\"\" part=\"0\" file=\"");
        push_xml_attr(&mut s, file);
        s.push_str("\"/>\n");
    }
    s.push_str("  </Collection>\n");
    s.push_str("</VTKFile>\n");
    s
}

/// Rejects stems that are not a plain file name.
fn check_stem(stem: &str) -> Result<(), VtkError> {
    let reason = if stem.is_empty() {
        Some("empty")
    } else if stem.contains(['/', '\\']) {
        Some("contains a path separator")
    } else if stem.contains('\0') {
        Some("contains a NUL character")
    } else if stem == "." || stem == ".." {
        Some("is `.` or `..`")
    } else {
        None
    };
    match reason {
        Some(reason) => Err(VtkError::InvalidStem { stem: stem.to_owned(), reason }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Field;

    const POINTS: [[f64; 3]; 4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    const TETS: [[u32; 4]; 1] = [[0, 1, 2, 3]];

    fn temp_dir(name: &str) -> PathBuf {
        std::env::temp_dir().join(format!("femdem-vtk-{name}-{}", std::process::id()))
    }

    /// `(timestep, file)` of every `DataSet` line of a pvd.
    fn datasets(pvd: &str) -> Vec<(String, String)> {
        let attr = |line: &str, key: &str| {
            let start = line.find(&format!(" {key}=\"")).unwrap() + key.len() + 3;
            let len = line[start..].find('"').unwrap();
            line[start..start + len].to_owned()
        };
        pvd.lines()
            .filter(|l| l.trim_start().starts_with("<DataSet "))
            .map(|l| (attr(l, "timestep"), attr(l, "file")))
            .collect()
    }

    #[test]
    fn pvd_lists_every_step_written_so_far() {
        let dir = temp_dir("series").join("nested");
        let mut series = SeriesWriter::new(&dir, "run").unwrap();
        assert!(series.is_empty());
        let region = [3.0];
        let cf = [Field::scalar("region", &region)];
        let frame = Frame::new(&POINTS, &TETS).with_cell_fields(&cf);
        let times = [0.0, 1e-7, 0.1 + 0.2];
        for (i, &t) in times.iter().enumerate() {
            let path = series.write(t, &frame).unwrap();
            assert_eq!(path, dir.join(format!("run_{i:06}.vtu")));
            assert!(path.is_file());

            let pvd = fs::read_to_string(series.pvd_path()).unwrap();
            assert!(pvd.starts_with("<?xml"), "{pvd}");
            assert!(pvd.contains(r#"<VTKFile type="Collection""#), "{pvd}");
            assert_eq!(pvd.matches("<Collection>").count(), 1, "{pvd}");
            assert!(pvd.trim_end().ends_with("</VTKFile>"), "{pvd}");
            let sets = datasets(&pvd);
            assert_eq!(sets.len(), i + 1, "{pvd}");
            for (j, (ts, file)) in sets.iter().enumerate() {
                assert_eq!(ts.parse::<f64>().unwrap().to_bits(), times[j].to_bits());
                assert_eq!(file, &format!("run_{j:06}.vtu"));
            }
        }
        assert_eq!(series.len(), 3);
        assert!(!crate::file::temp_path(&series.pvd_path()).exists());
        fs::remove_dir_all(temp_dir("series")).unwrap();
    }

    #[test]
    fn a_resumed_series_lists_the_steps_kept_and_continues_after_them() {
        let dir = temp_dir("series-resume");
        let frame = Frame::new(&POINTS, &TETS);
        let mut series = SeriesWriter::new(&dir, "s").unwrap();
        for t in [0.0, 1.0, 2.0] {
            series.write(t, &frame).unwrap();
        }
        assert_eq!(series.times(), [0.0, 1.0, 2.0]);
        let mut resumed = SeriesWriter::resume(&dir, "s", &[0.0, 1.0]).unwrap();
        let pvd = fs::read_to_string(resumed.pvd_path()).unwrap();
        assert_eq!(datasets(&pvd).len(), 2, "{pvd}");
        let path = resumed.write(1.5, &frame).unwrap();
        assert!(path.ends_with("s_000002.vtu"));
        let sets = datasets(&fs::read_to_string(resumed.pvd_path()).unwrap());
        assert_eq!(sets[2], ("1.5".to_string(), "s_000002.vtu".to_string()));
        let err = SeriesWriter::resume(&dir, "s", &[0.0, 1.0, 2.0, 3.0]).unwrap_err();
        assert!(matches!(err, VtkError::Resume { .. }) && err.to_string().contains("s_000003.vtu"), "{err}");
        let err = SeriesWriter::resume(&dir, "s", &[1.0, 0.0]).unwrap_err();
        assert!(matches!(err, VtkError::Resume { .. }), "{err}");
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn times_must_increase_and_be_finite() {
        let dir = temp_dir("series-time");
        let mut series = SeriesWriter::new(&dir, "s").unwrap();
        let frame = Frame::new(&POINTS, &TETS);
        series.write(1.0, &frame).unwrap();
        for bad in [1.0, 0.5, f64::NAN, f64::INFINITY] {
            let err = series.write(bad, &frame).unwrap_err();
            assert!(matches!(err, VtkError::BadTime { .. }), "{err}");
        }
        assert_eq!(series.len(), 1);
        assert!(!dir.join("s_000001.vtu").exists());
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn failed_step_is_not_listed() {
        let dir = temp_dir("series-fail");
        let mut series = SeriesWriter::new(&dir, "s").unwrap();
        series.write(0.0, &Frame::new(&POINTS, &TETS)).unwrap();
        let err = series.write(1.0, &Frame::new(&POINTS, &[[0, 1, 2, 9]])).unwrap_err();
        assert!(matches!(err, VtkError::NodeOutOfRange { .. }), "{err}");
        assert_eq!(series.len(), 1);
        let pvd = fs::read_to_string(series.pvd_path()).unwrap();
        assert_eq!(datasets(&pvd).len(), 1);
        // The next good step takes the index the failed one would have had.
        let path = series.write(1.0, &Frame::new(&POINTS, &TETS)).unwrap();
        assert!(path.ends_with("s_000001.vtu"));
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn stems_must_be_plain_file_names() {
        let dir = temp_dir("series-stem");
        for bad in ["", "a/b", r"a\b", ".", "..", "a\0b"] {
            let err = SeriesWriter::new(&dir, bad).unwrap_err();
            assert!(matches!(err, VtkError::InvalidStem { .. }), "{bad:?}: {err}");
        }
        assert!(!dir.exists(), "nothing is created for a bad stem");
    }

    #[test]
    fn file_names_are_escaped_in_the_pvd() {
        let text = pvd_text(&[(0.5, "a&b_000000.vtu".to_owned())]);
        assert!(text.contains(r#"file="a&amp;b_000000.vtu""#), "{text}");
        assert!(text.contains(r#"timestep="0.5""#), "{text}");
    }
}
