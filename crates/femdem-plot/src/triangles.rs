//! Maps of flat coloured triangles in a plane (fracture patterns, stress
//! on a section).

use std::ops::Range;
use std::path::Path;

use plotters::prelude::*;

use crate::style::{legend_box, register_font};
use crate::{PlotError, check_png};

/// Draws filled triangles in a plane, each with its colour, into the PNG
/// file `path`: `axes` are the axis labels, `bounds` the `(x, y)` ranges
/// in the triangles' units (the image is 700 px of x wide, its height
/// following the ranges' aspect), `legend` names colours (drawn as
/// swatches, top right, when not empty) and `edges` outlines each triangle.
///
/// # Errors
/// A [`PlotError`] naming `path` if it does not end in `.png` or cannot be
/// written.
pub fn triangles(
    path: &Path,
    title: &str,
    axes: (&str, &str),
    bounds: (Range<f64>, Range<f64>),
    tris: &[([(f64, f64); 3], RGBColor)],
    legend: &[(String, RGBColor)],
    edges: bool,
) -> Result<(), PlotError> {
    check_png(path)?;
    register_font();
    let fail = |e| PlotError::drawing(path, e);
    let (xr, yr) = bounds;
    let side = 700u32;
    let aspect = (yr.end - yr.start) / (xr.end - xr.start);
    let root = BitMapBackend::new(path, (side + 80, (f64::from(side) * aspect) as u32 + 110)).into_drawing_area();
    root.fill(&WHITE).map_err(fail)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(40)
        .y_label_area_size(55)
        .build_cartesian_2d(xr, yr)
        .map_err(fail)?;
    chart.configure_mesh().x_desc(axes.0).y_desc(axes.1).label_style(("sans-serif", 14)).draw().map_err(fail)?;
    chart.draw_series(tris.iter().map(|(p, c)| Polygon::new(p.to_vec(), c.filled()))).map_err(fail)?;
    if edges {
        chart
            .draw_series(tris.iter().map(|(p, _)| PathElement::new(vec![p[0], p[1], p[2], p[0]], BLACK.mix(0.25))))
            .map_err(fail)?;
    }
    for (name, c) in legend {
        let c = *c;
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), u32>>())
            .map_err(fail)?
            .label(name.as_str())
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 12, y + 5)], c.filled()));
    }
    if !legend.is_empty() {
        legend_box(&mut chart, SeriesLabelPosition::UpperRight, 14).map_err(fail)?;
    }
    root.present().map_err(fail)?;
    Ok(())
}
