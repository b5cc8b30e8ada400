//! Joint failures as `femdem run` records them in `failures.csv`: one row
//! per failed joint, with the centroid of its mid-plane and its mode; and
//! the colours the figures give the modes.

use std::path::Path;

use anyhow::Result;
use plotters::style::RGBColor;

use crate::validate::history::Table;

/// One row of `failures.csv`.
#[derive(Debug, Clone, Copy)]
pub struct Failure {
    /// Start of the step that broke the joint, s.
    pub time: f64,
    /// Centroid of the joint's mid-plane, m.
    pub at: [f64; 3],
    /// Mode code: 1 tensile, 2 shear, 3 mixed, 4 collapsed.
    pub mode: u8,
}

/// Counts of failures by mode.
#[derive(Debug, Clone, Copy, Default)]
pub struct Modes {
    /// Tensile, shear, mixed, collapsed.
    pub counts: [usize; 4],
}

impl Modes {
    /// Counts the failures `f` by mode.
    pub fn of<'a>(f: impl Iterator<Item = &'a Failure>) -> Modes {
        let mut m = Modes::default();
        for x in f {
            if (1..=4).contains(&x.mode) {
                m.counts[usize::from(x.mode) - 1] += 1;
            }
        }
        m
    }

    /// All counted failures.
    pub fn total(&self) -> usize {
        self.counts.iter().sum()
    }

    /// Share of mode `code` (1–4).
    pub fn share(&self, code: usize) -> f64 {
        self.counts[code - 1] as f64 / self.total().max(1) as f64
    }

    /// `T/S/M/C` counts as text.
    pub fn text(&self) -> String {
        let [t, s, m, c] = self.counts;
        format!("T {t} / S {s} / M {m} / C {c}")
    }
}

impl Failure {
    /// Every row of `dir/failures.csv`.
    pub fn read_all(dir: &Path) -> Result<Vec<Failure>> {
        let f = Table::read(&dir.join("failures.csv"))?;
        let (ft, fx, fy, fz, fm) = (f.col("time")?, f.col("x")?, f.col("y")?, f.col("z")?, f.col("mode")?);
        Ok((0..f.len()).map(|i| Failure { time: ft[i], at: [fx[i], fy[i], fz[i]], mode: fm[i] as u8 }).collect())
    }
}

/// Colour of failure mode `code` (0 pre-existing … 4 collapsed).
pub fn mode_colour(code: f64) -> RGBColor {
    match code as i64 {
        1 => RGBColor(214, 39, 40),
        2 => RGBColor(31, 119, 180),
        3 => RGBColor(255, 127, 14),
        4 => RGBColor(127, 127, 127),
        _ => RGBColor(0, 0, 0),
    }
}

/// The legend of [`mode_colour`].
pub fn mode_legend() -> Vec<(String, RGBColor)> {
    ["tensile", "shear", "mixed", "collapsed"]
        .iter()
        .zip(1..)
        .map(|(n, c)| ((*n).to_owned(), mode_colour(f64::from(c))))
        .collect()
}
