//! Figures of the validation report, drawn with plotters into PNG files
//! with the bundled DejaVu Sans (`xtask/assets`).

use std::path::Path;
use std::sync::Once;

use anyhow::{Result, anyhow};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::FontStyle;

const FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// Registers the bundled font as `sans-serif` (once).
pub fn font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        plotters::style::register_font("sans-serif", FontStyle::Normal, FONT)
            .unwrap_or_else(|_| panic!("the bundled DejaVuSans.ttf is not a font"));
    });
}

pub fn err<E: std::fmt::Debug>(e: E) -> anyhow::Error {
    anyhow!("drawing a figure: {e:?}")
}

/// A qualitative colour for series `i`.
pub fn series_colour(i: usize) -> RGBColor {
    const C: [RGBColor; 8] = [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
        RGBColor(214, 39, 40),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(0, 0, 0),
        RGBColor(150, 150, 150),
    ];
    C[i % C.len()]
}

/// Padded range of `values` (never empty).
fn range(values: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    if !lo.is_finite() || !hi.is_finite() {
        return 0.0..1.0;
    }
    let pad = 0.05 * (hi - lo).max(1e-30);
    (lo - pad)..(hi + pad)
}

/// Line plot of named `(x, y)` series on one chart.
pub fn lines(path: &Path, title: &str, x_desc: &str, y_desc: &str, series: &[(String, Vec<(f64, f64)>)]) -> Result<()> {
    font();
    let root = BitMapBackend::new(path, (900, 600)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let xs = range(series.iter().flat_map(|(_, p)| p.iter().map(|q| q.0)));
    let ys = range(series.iter().flat_map(|(_, p)| p.iter().map(|q| q.1)).chain([0.0]));
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(xs, ys)
        .map_err(err)?;
    chart.configure_mesh().x_desc(x_desc).y_desc(y_desc).label_style(("sans-serif", 15)).draw().map_err(err)?;
    for (i, (name, points)) in series.iter().enumerate() {
        let c = series_colour(i);
        chart
            .draw_series(LineSeries::new(points.iter().copied(), c.stroke_width(2)))
            .map_err(err)?
            .label(name.as_str())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
    }
    legend_box(&mut chart, SeriesLabelPosition::UpperLeft, 15)?;
    root.present().map_err(err)?;
    Ok(())
}

/// Filled triangles in a plane, each with a colour; `legend` names the
/// colours; `edges` outlines each triangle. `bounds` is `(x range, y range)` in the triangles' units.
pub fn triangles(
    path: &Path,
    title: &str,
    axes: (&str, &str),
    bounds: (std::ops::Range<f64>, std::ops::Range<f64>),
    tris: &[([(f64, f64); 3], RGBColor)],
    legend: &[(String, RGBColor)],
    edges: bool,
) -> Result<()> {
    font();
    let (xr, yr) = bounds;
    let side = 700u32;
    let aspect = (yr.end - yr.start) / (xr.end - xr.start);
    let root = BitMapBackend::new(path, (side + 80, (f64::from(side) * aspect) as u32 + 110)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(40)
        .y_label_area_size(55)
        .build_cartesian_2d(xr, yr)
        .map_err(err)?;
    chart.configure_mesh().x_desc(axes.0).y_desc(axes.1).label_style(("sans-serif", 14)).draw().map_err(err)?;
    chart.draw_series(tris.iter().map(|(p, c)| Polygon::new(p.to_vec(), c.filled()))).map_err(err)?;
    if edges {
        chart
            .draw_series(tris.iter().map(|(p, _)| PathElement::new(vec![p[0], p[1], p[2], p[0]], BLACK.mix(0.25))))
            .map_err(err)?;
    }
    for (name, c) in legend {
        let c = *c;
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), u32>>())
            .map_err(err)?
            .label(name.as_str())
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 12, y + 5)], c.filled()));
    }
    if !legend.is_empty() {
        legend_box(&mut chart, SeriesLabelPosition::UpperRight, 14)?;
    }
    root.present().map_err(err)?;
    Ok(())
}

/// Draws the legend of `chart`'s labelled series in a framed box at `at`.
fn legend_box<'a, DB: DrawingBackend + 'a>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    at: SeriesLabelPosition,
    font_size: u32,
) -> Result<()> {
    chart
        .configure_series_labels()
        .position(at)
        .label_font(("sans-serif", font_size))
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()
        .map_err(err)
}

/// Diverging colour map: blue (−1) through white (0) to red (+1); `s` is
/// clamped to [−1, 1].
pub fn diverging(s: f64) -> RGBColor {
    let s = s.clamp(-1.0, 1.0);
    let mix = |a: u8, b: u8, t: f64| (f64::from(a) + (f64::from(b) - f64::from(a)) * t).round() as u8;
    if s >= 0.0 {
        RGBColor(mix(255, 178, s), mix(255, 24, s), mix(255, 43, s))
    } else {
        RGBColor(mix(255, 33, -s), mix(255, 102, -s), mix(255, 172, -s))
    }
}
