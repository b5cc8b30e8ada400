//! The CSV files `femdem run` writes (`history.csv`, `failures.csv`), read
//! as named columns of numbers, with the comment lines a history starts
//! with (its case, title, overrides and provenance).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

/// A CSV file of numbers with a header row, as read.
#[derive(Debug, Clone)]
pub struct Table {
    /// The file.
    pub path: PathBuf,
    /// The leading `#` lines, without the `#` and the space after it.
    pub comments: Vec<String>,
    /// The column names.
    pub columns: Vec<String>,
    /// The rows, one value per column.
    pub rows: Vec<Vec<f64>>,
}

impl Table {
    /// Reads `path`: comment lines, a header (RFC 4180 quoting), rows of
    /// numbers; blank lines are skipped. A last line without its line
    /// break (a run still writing) is left out.
    ///
    /// # Errors
    /// An unreadable file, a file with no header, or a row that is not as
    /// many numbers as there are columns (named by file and line).
    pub fn read(path: &Path) -> Result<Table> {
        let text = std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        let complete = if text.ends_with('\n') { &text[..] } else { &text[..text.rfind('\n').map_or(0, |i| i + 1)] };
        let mut comments = Vec::new();
        let mut columns = None;
        let mut rows = Vec::new();
        for (i, line) in complete.lines().enumerate() {
            let line = line.trim_end_matches('\r');
            if line.trim().is_empty() {
                continue;
            }
            if columns.is_none() {
                if let Some(c) = line.strip_prefix('#') {
                    comments.push(c.strip_prefix(' ').unwrap_or(c).to_owned());
                } else {
                    columns = Some(header_names(line));
                }
                continue;
            }
            let n = columns.as_ref().map_or(0, Vec::len);
            let row = line
                .split(',')
                .map(|v| v.trim().parse::<f64>())
                .collect::<Result<Vec<f64>, _>>()
                .with_context(|| format!("{}:{}: not a row of numbers", path.display(), i + 1))?;
            if row.len() != n {
                bail!("{}:{}: {} values for {n} columns", path.display(), i + 1, row.len());
            }
            rows.push(row);
        }
        let Some(columns) = columns else {
            bail!("{} is empty: it has no header line (did the run start?)", path.display());
        };
        Ok(Table { path: path.to_owned(), comments, columns, rows })
    }

    /// The history of a run: `dir/history.csv`.
    ///
    /// # Errors
    /// As [`Table::read`].
    pub fn history(dir: &Path) -> Result<Table> {
        Table::read(&dir.join("history.csv"))
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// Whether there is no row.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// The index of column `name`.
    ///
    /// # Errors
    /// When there is no such column; the message lists those there are.
    pub fn index(&self, name: &str) -> Result<usize> {
        self.columns.iter().position(|c| c == name).with_context(|| {
            format!("{} has no column `{name}`; its columns are: {}", self.path.display(), self.columns.join(", "))
        })
    }

    /// The values of column `name`, one per row.
    ///
    /// # Errors
    /// As [`Table::index`].
    pub fn col(&self, name: &str) -> Result<Vec<f64>> {
        let i = self.index(name)?;
        Ok(self.rows.iter().map(|r| r[i]).collect())
    }

    /// The `(x, y)` points of columns `x` and `y` (indices).
    pub fn points(&self, x: usize, y: usize) -> Vec<(f64, f64)> {
        self.rows.iter().map(|r| (r[x], r[y])).collect()
    }

    /// The value of the comment `key: value`, if there is one.
    pub fn comment(&self, key: &str) -> Option<&str> {
        self.comments.iter().find_map(|c| c.strip_prefix(key)?.strip_prefix(':').map(str::trim))
    }

    /// What a figure calls the run: the case's title, else its file name,
    /// else the results' folder.
    pub fn label(&self) -> String {
        self.comment("title").or_else(|| self.comment("case")).map_or_else(
            || {
                let dir = self.path.parent().and_then(Path::file_name);
                dir.map_or_else(|| self.path.display().to_string(), |d| d.to_string_lossy().into_owned())
            },
            str::to_owned,
        )
    }

    /// The work of the face loads at the last row, summed by the axis their
    /// group's side names (`xmin`/`xmax`, `ymin`/`ymax`, `bottom`/`top`, the
    /// extrusion's z faces); `None` when no load's work is recorded. A drive's
    /// work (a `<name>_work` whose name also has `<name>_uz`) is not a face
    /// load's and is left out.
    ///
    /// # Errors
    /// Only if a column listed cannot be read back, which [`Table::read`]
    /// rules out.
    pub fn face_work_by_axis(&self) -> Result<Option<[f64; 3]>> {
        let mut w = [0.0; 3];
        let mut any = false;
        for name in &self.columns {
            let Some(group) = name.strip_suffix("_work") else { continue };
            if self.columns.iter().any(|c| c.strip_suffix("_uz") == Some(group)) {
                continue;
            }
            let side = group.rsplit('.').next().unwrap_or(group);
            let axis = match side {
                "xmin" | "xmax" => 0,
                "ymin" | "ymax" => 1,
                "bottom" | "top" => 2,
                _ => continue,
            };
            w[axis] += self.col(name)?.last().copied().unwrap_or(0.0);
            any = true;
        }
        Ok(any.then_some(w))
    }

    /// The largest |balance| / external work over the rows once the work
    /// has reached 10% of its final value (earlier, both are tiny and their
    /// ratio is noise): the run's energy-balance error.
    ///
    /// # Errors
    /// When the table has no `external_work` or `balance` column.
    pub fn energy_error(&self) -> Result<f64> {
        let (work, balance) = (self.col("external_work")?, self.col("balance")?);
        let w_end = work.last().copied().unwrap_or(0.0);
        Ok(work
            .iter()
            .zip(&balance)
            .filter(|(w, _)| **w >= 0.1 * w_end && **w > 0.0)
            .map(|(w, b)| b.abs() / w)
            .fold(0.0, f64::max))
    }
}

/// The names of a CSV header line, unquoted as RFC 4180 quotes them.
fn header_names(line: &str) -> Vec<String> {
    let mut names = Vec::new();
    let mut name = String::new();
    let (mut quoted, mut chars) = (false, line.chars().peekable());
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                chars.next();
                name.push('"');
            }
            ('"', _) => quoted = !quoted,
            (',', false) => names.push(std::mem::take(&mut name)),
            (c, _) => name.push(c),
        }
    }
    names.push(name);
    names.into_iter().map(|n| n.trim().to_owned()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quoted_header_names_are_unquoted() {
        assert_eq!(header_names(r#"time,"a,b","say ""hi""",x"#), ["time", "a,b", "say \"hi\"", "x"]);
        assert_eq!(header_names("time"), ["time"]);
    }

    #[test]
    fn a_history_is_read_past_its_comments_and_without_a_partial_last_line() {
        let path = std::env::temp_dir().join(format!("femdem-post-read-{}.csv", std::process::id()));
        std::fs::write(&path, "# case: bar.toml\n# title: A bar\ntime,\"x,y\"\n0,1\n\n1,2\n2,").unwrap();
        let h = Table::read(&path).unwrap();
        assert_eq!(h.comments, ["case: bar.toml", "title: A bar"]);
        assert_eq!(h.columns, ["time", "x,y"]);
        assert_eq!(h.rows, [vec![0.0, 1.0], vec![1.0, 2.0]]);
        assert_eq!(h.col("x,y").unwrap(), [1.0, 2.0]);
        assert_eq!(h.label(), "A bar");
        let err = h.index("z").unwrap_err().to_string();
        assert!(err.contains("no column `z`") && err.contains("time, x,y"), "{err}");
        std::fs::write(&path, "time,x\n0,1\n1\n").unwrap();
        let err = Table::read(&path).unwrap_err().to_string();
        assert!(err.ends_with(":3: 1 values for 2 columns"), "{err}");
        std::fs::write(&path, "# only a comment\n").unwrap();
        let err = Table::read(&path).unwrap_err().to_string();
        assert!(err.contains("no header line"), "{err}");
        std::fs::remove_file(&path).unwrap();
    }

    #[test]
    fn the_face_loads_work_is_summed_by_axis_and_absent_from_an_older_history() {
        let dir = std::env::temp_dir().join(format!("femdem-post-work-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("history.csv");
        std::fs::write(
            &path,
            "# case: c.toml\ntime,external_work,block.xmin_fx,block.xmin_work,block.xmax_work,block.ymin_work,block.ymax_work,\
             block.bottom_work,block.top_work,platen_work,held.xmin_uz,held.xmin_work\n\
             0,0,0,0,0,0,0,0,0,0,0,0\n1,21,5,1,2,3,4,5,6,100,0,50\n",
        )
        .unwrap();
        let w = Table::read(&path).unwrap().face_work_by_axis().unwrap();
        assert_eq!(w, Some([3.0, 7.0, 11.0]), "x, y, z faces; another side's column or a drive's is not counted");
        std::fs::write(&path, "time,external_work,block.xmin_fx\n0,0,0\n").unwrap();
        assert_eq!(Table::read(&path).unwrap().face_work_by_axis().unwrap(), None);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn the_energy_error_is_read_once_the_work_is_a_tenth_of_its_final_value() {
        let path = std::env::temp_dir().join(format!("femdem-post-energy-{}.csv", std::process::id()));
        // Row 1: work 0.05 of the final (ratio 1.0 ignored); rows 2-3: 0.02 and 0.01.
        std::fs::write(&path, "external_work,balance\n0.5,0.5\n5,0.1\n10,-0.1\n").unwrap();
        let h = Table::read(&path).unwrap();
        assert!((h.energy_error().unwrap() - 0.02).abs() < 1e-15);
        std::fs::remove_file(&path).unwrap();
    }
}
