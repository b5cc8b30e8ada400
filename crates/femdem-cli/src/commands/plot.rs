//! `femdem plot RESULTS [--x COL] [--y COL]... [--out FILE]`: PNG plots of
//! a run's `history.csv`, drawn by `femdem-plot` (the code that draws the
//! validation's figures). Without `--y`: the energies and the failed
//! joints against time, and the load against the strain when the run has
//! `[output.load_strain]`, as `plot_*.png` beside the history.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use femdem_plot::{LineChart, Series};

/// What `femdem plot` was asked for, beyond the results.
#[derive(Clone, Debug, Default)]
pub struct PlotOptions {
    /// `--x COL` (default `time`).
    pub x: Option<String>,
    /// `--y COL`, repeatable: the columns drawn against `x`.
    pub y: Vec<String>,
    /// `--out FILE`: the PNG file (default `plot_<y>_vs_<x>.png` beside the
    /// history).
    pub out: Option<PathBuf>,
}

/// The energy columns of a history, in the order drawn.
const ENERGIES: [&str; 9] = femdem_run::output::ENERGY_COLUMNS;

/// The failure counts of a history, by mode.
const FAILURES: [&str; 4] = ["broken_tensile", "broken_shear", "broken_mixed", "broken_collapsed"];

/// A `history.csv` as read: its comment lines, columns and rows.
#[derive(Debug)]
pub struct History {
    /// The file.
    pub path: PathBuf,
    /// The leading `#` lines, without the `#` and the space after it.
    pub comments: Vec<String>,
    /// The column names.
    pub columns: Vec<String>,
    /// The rows, one value per column.
    pub rows: Vec<Vec<f64>>,
}

impl History {
    /// Reads `path`: comment lines, a header (RFC 4180 quoting), rows of
    /// numbers. A last line without its line break (a run still writing)
    /// is left out.
    pub fn read(path: &Path) -> Result<History> {
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
        Ok(History { path: path.to_owned(), comments, columns, rows })
    }

    /// The index of column `name`, or an error listing the columns there are.
    pub fn index(&self, name: &str) -> Result<usize> {
        self.columns.iter().position(|c| c == name).with_context(|| {
            format!("{} has no column `{name}`; its columns are: {}", self.path.display(), self.columns.join(", "))
        })
    }

    /// The `(x, y)` points of columns `x` and `y` (indices).
    fn points(&self, x: usize, y: usize) -> Vec<(f64, f64)> {
        self.rows.iter().map(|r| (r[x], r[y])).collect()
    }

    /// The value of the comment `key: value`, if there is one.
    fn comment(&self, key: &str) -> Option<&str> {
        self.comments.iter().find_map(|c| c.strip_prefix(key)?.strip_prefix(':').map(str::trim))
    }

    /// What the plots' captions call the run: the case's title, else its
    /// file name, else the results' folder.
    fn label(&self) -> String {
        self.comment("title").or_else(|| self.comment("case")).map_or_else(
            || {
                let dir = self.path.parent().and_then(Path::file_name);
                dir.map_or_else(|| self.path.display().to_string(), |d| d.to_string_lossy().into_owned())
            },
            str::to_owned,
        )
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

/// The unit of a column `femdem run` writes, when it has one.
fn unit(column: &str) -> Option<&'static str> {
    if column == "time" {
        Some("s")
    } else if ENERGIES.contains(&column) || column.ends_with("_work") {
        Some("J")
    } else if column == "load" || ["_fx", "_fy", "_fz"].iter().any(|s| column.ends_with(s)) {
        Some("N")
    } else if ["_ux", "_uy", "_uz"].iter().any(|s| column.ends_with(s)) {
        Some("m")
    } else {
        None
    }
}

/// An axis label: the column names, with their unit when they share one.
fn axis_label(columns: &[&str]) -> String {
    let names = columns.join(", ");
    let units: Vec<Option<&str>> = columns.iter().map(|c| unit(c)).collect();
    match units.first() {
        Some(&Some(u)) if units.iter().all(|&v| v == Some(u)) => format!("{names} ({u})"),
        _ => names,
    }
}

/// A file name made of `text`: letters, digits, `-`, `_` and `.` kept,
/// anything else `_`.
fn file_safe(text: &str) -> String {
    text.chars().map(|c| if c.is_ascii_alphanumeric() || "-_.".contains(c) { c } else { '_' }).collect()
}

/// The history of `results`: a results directory (its `history.csv`) or a
/// history file itself.
fn history_path(results: &Path) -> Result<PathBuf> {
    if results.is_file() {
        return Ok(results.to_owned());
    }
    if !results.is_dir() {
        bail!("{}: no such directory (give the output directory of `femdem run`)", results.display());
    }
    let path = results.join("history.csv");
    if !path.is_file() {
        bail!(
            "{} holds no history.csv: is it the output directory of `femdem run`? (the run writes it as it starts)",
            results.display()
        );
    }
    Ok(path)
}

/// Runs the command: writes the plots and prints their paths.
pub fn run(results: &Path, options: PlotOptions) -> Result<()> {
    let history = History::read(&history_path(results)?)?;
    if history.rows.is_empty() {
        bail!("{} has no rows yet: the run wrote its header and no step", history.path.display());
    }
    let dir = history.path.parent().map_or_else(PathBuf::new, Path::to_path_buf);
    let label = history.label();
    let mut written = Vec::new();
    if options.y.is_empty() {
        for (name, plot) in default_plots(&history, &label)? {
            let path = dir.join(format!("plot_{name}.png"));
            plot.draw(&path)?;
            written.push(path);
        }
    } else {
        let x = options.x.as_deref().unwrap_or("time");
        let xi = history.index(x)?;
        let ys: Vec<&str> = options.y.iter().map(String::as_str).collect();
        let series = ys
            .iter()
            .map(|y| Ok(((*y).to_owned(), history.points(xi, history.index(y)?))))
            .collect::<Result<Vec<Series>>>()?;
        let path = match options.out {
            Some(out) => out,
            None => dir.join(format!("plot_{}_vs_{}.png", file_safe(&ys.join("-")), file_safe(x))),
        };
        if path.is_dir() {
            bail!("--out {}: it is a directory; name a .png file", path.display());
        }
        if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
            std::fs::create_dir_all(parent).with_context(|| format!("creating the folder {}", parent.display()))?;
        }
        let title = format!("{label} — {} against {x}", ys.join(", "));
        Plot { title, x: axis_label(&[x]), y: axis_label(&ys), series }.draw(&path)?;
        written.push(path);
    }
    for path in written {
        println!("{}", path.display());
    }
    Ok(())
}

/// One figure to draw.
struct Plot {
    title: String,
    x: String,
    y: String,
    series: Vec<Series>,
}

impl Plot {
    fn draw(&self, path: &Path) -> Result<()> {
        LineChart::new(&self.title, &self.x, &self.y).scaled().draw(path, &self.series)?;
        Ok(())
    }
}

/// The plots drawn without `--y`, by name: the load against the strain
/// (when the history has them), the energies and the failed joints against
/// time. Series that stay zero throughout are left out (the balance and
/// the total of failed joints are always drawn).
fn default_plots(h: &History, label: &str) -> Result<Vec<(&'static str, Plot)>> {
    let t = h.index("time")?;
    let nonzero = |c: usize| h.rows.iter().any(|r| r[c] != 0.0);
    let mut plots = Vec::new();
    if let (Ok(load), Ok(strain)) = (h.index("load"), h.index("strain")) {
        let series = vec![("load".to_owned(), h.points(strain, load))];
        let title = format!("{label} — load against strain");
        plots.push(("load_strain", Plot { title, x: axis_label(&["strain"]), y: axis_label(&["load"]), series }));
    }
    let energies: Vec<Series> = ENERGIES
        .iter()
        .filter_map(|&e| h.index(e).ok().map(|i| (e, i)))
        .filter(|&(e, i)| e == "balance" || nonzero(i))
        .map(|(e, i)| (e.to_owned(), h.points(t, i)))
        .collect();
    if !energies.is_empty() {
        let title = format!("{label} — energies");
        plots.push(("energies", Plot { title, x: axis_label(&["time"]), y: "energy (J)".into(), series: energies }));
    }
    let modes: Vec<(&str, usize)> = FAILURES.iter().filter_map(|&m| h.index(m).ok().map(|i| (m, i))).collect();
    if !modes.is_empty() {
        let total: Vec<(f64, f64)> = h.rows.iter().map(|r| (r[t], modes.iter().map(|&(_, i)| r[i]).sum())).collect();
        let mut series = vec![("all".to_owned(), total)];
        series.extend(
            modes
                .iter()
                .filter(|&&(_, i)| nonzero(i))
                .map(|&(m, i)| (m.trim_start_matches("broken_").to_owned(), h.points(t, i))),
        );
        let title = format!("{label} — failed joints");
        plots.push(("failures", Plot { title, x: axis_label(&["time"]), y: "failed joints".into(), series }));
    }
    Ok(plots)
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
    fn axis_labels_carry_a_shared_unit() {
        assert_eq!(axis_label(&["time"]), "time (s)");
        assert_eq!(axis_label(&["kinetic", "fracture"]), "kinetic, fracture (J)");
        assert_eq!(axis_label(&["platen_top_fy", "load"]), "platen_top_fy, load (N)");
        assert_eq!(axis_label(&["load", "strain"]), "load, strain");
        assert_eq!(axis_label(&["disc_uy"]), "disc_uy (m)");
        assert_eq!(file_safe("a/b c-d_e.f"), "a_b_c-d_e.f");
    }

    #[test]
    fn a_history_is_read_past_its_comments_and_without_a_partial_last_line() {
        let path = std::env::temp_dir().join(format!("femdem-plot-read-{}.csv", std::process::id()));
        std::fs::write(&path, "# case: bar.toml\n# title: A bar\ntime,\"x,y\"\n0,1\n\n1,2\n2,").unwrap();
        let h = History::read(&path).unwrap();
        assert_eq!(h.comments, ["case: bar.toml", "title: A bar"]);
        assert_eq!(h.columns, ["time", "x,y"]);
        assert_eq!(h.rows, [vec![0.0, 1.0], vec![1.0, 2.0]]);
        assert_eq!(h.label(), "A bar");
        let err = h.index("z").unwrap_err().to_string();
        assert!(err.contains("no column `z`") && err.contains("time, x,y"), "{err}");
        std::fs::write(&path, "time,x\n0,1\n1\n").unwrap();
        let err = History::read(&path).unwrap_err().to_string();
        assert!(err.contains(":3: 1 values for 2 columns"), "{err}");
        std::fs::remove_file(&path).unwrap();
    }
}
