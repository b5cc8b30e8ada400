//! Figures of the validation report: `femdem-plot`'s line charts and
//! triangle maps (the code `femdem plot` draws with too), with `anyhow`
//! errors.

use std::ops::Range;
use std::path::Path;

use anyhow::{Result, anyhow};
use plotters::style::RGBColor;

pub use femdem_plot::diverging;

/// An error of plotters' drawing, as `anyhow`.
pub fn err<E: std::fmt::Debug>(e: E) -> anyhow::Error {
    anyhow!("drawing a figure: {e:?}")
}

/// Line plot of named `(x, y)` series on one chart ([`femdem_plot::lines`]).
pub fn lines(path: &Path, title: &str, x_desc: &str, y_desc: &str, series: &[(String, Vec<(f64, f64)>)]) -> Result<()> {
    Ok(femdem_plot::lines(path, title, x_desc, y_desc, series)?)
}

/// Filled triangles in a plane, each with a colour; `legend` names the
/// colours; `edges` outlines each triangle. `bounds` is `(x range, y range)`
/// in the triangles' units ([`femdem_plot::triangles`]).
pub fn triangles(
    path: &Path,
    title: &str,
    axes: (&str, &str),
    bounds: (Range<f64>, Range<f64>),
    tris: &[([(f64, f64); 3], RGBColor)],
    legend: &[(String, RGBColor)],
    edges: bool,
) -> Result<()> {
    Ok(femdem_plot::triangles(path, title, axes, bounds, tris, legend, edges)?)
}
