//! `femdem plot RESULTS [--x COL] [--y COL]... [--out FILE]`: PNG plots of
//! a run's `history.csv`, drawn by `femdem-plot` (the code that draws the
//! validation's figures). Without `--y`: the energies and the failed
//! joints against time, and the load against the strain when the run has
//! `[output.load_strain]`, as `plot_*.png` beside the history.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use femdem_plot::{LineChart, Series};
use femdem_post::columns::{BROKEN, ENERGY, unit};
use femdem_post::table::Table as History;

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
    // A run's history: named so, or with its `time` and `step` columns (a
    // run writes the header as it starts, a row at each output interval).
    let named = history.path.file_name().is_some_and(|n| n == "history.csv");
    let is_history = named || (history.index("time").is_ok() && history.index("step").is_ok());
    if history.rows.is_empty() {
        if is_history {
            bail!("{} has no rows yet: the run wrote its header and no step", history.path.display());
        }
        bail!("{} has a header and no rows: nothing to draw", history.path.display());
    }
    let dir = history.path.parent().map_or_else(PathBuf::new, Path::to_path_buf);
    let label = history.label();
    let mut written = Vec::new();
    if options.y.is_empty() {
        let plots = default_plots(&history, &label)?;
        if plots.is_empty() {
            bail!(
                "{} has none of the columns `femdem plot` draws by default (load and strain, the energies, the \
                 failed joints){}: name the columns to draw with --y (and --x); its columns are: {}",
                history.path.display(),
                if is_history { "" } else { " — it is not a run's history.csv" },
                history.columns.join(", ")
            );
        }
        for (name, plot) in plots {
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
    if history.rows.len() == 1 {
        eprintln!(
            "warning: {} has one row: each curve is a single point, which a line plot does not show",
            history.path.display()
        );
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
    /// Draws the figure; points that are not finite (a NaN or ±inf in the
    /// history, from a run stopped by the guard, say) cannot be drawn and
    /// are named in a warning.
    fn draw(&self, path: &Path) -> Result<()> {
        for (name, points) in &self.series {
            let bad = points.iter().filter(|(x, y)| !(x.is_finite() && y.is_finite())).count();
            if bad > 0 {
                eprintln!(
                    "warning: {}: {bad} of the {} points of `{name}` are not finite (NaN or ±inf) and are not drawn",
                    path.display(),
                    points.len()
                );
            }
        }
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
    let energies: Vec<Series> = ENERGY
        .iter()
        .filter_map(|&e| h.index(e).ok().map(|i| (e, i)))
        .filter(|&(e, i)| e == "balance" || nonzero(i))
        .map(|(e, i)| (e.to_owned(), h.points(t, i)))
        .collect();
    if !energies.is_empty() {
        let title = format!("{label} — energies");
        plots.push(("energies", Plot { title, x: axis_label(&["time"]), y: "energy (J)".into(), series: energies }));
    }
    let modes: Vec<(&str, usize)> = BROKEN.iter().filter_map(|&m| h.index(m).ok().map(|i| (m, i))).collect();
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
    fn axis_labels_carry_a_shared_unit() {
        assert_eq!(axis_label(&["time"]), "time (s)");
        assert_eq!(axis_label(&["kinetic", "fracture"]), "kinetic, fracture (J)");
        assert_eq!(axis_label(&["platen_top_fy", "load"]), "platen_top_fy, load (N)");
        assert_eq!(axis_label(&["load", "strain"]), "load, strain");
        assert_eq!(axis_label(&["disc_uy"]), "disc_uy (m)");
        assert_eq!(file_safe("a/b c-d_e.f"), "a_b_c-d_e.f");
    }
}
