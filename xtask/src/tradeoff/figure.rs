//! The trade-off figure: peak-load error against wall time on log axes,
//! one colour per knob, the Pareto front drawn as a line; font, palette
//! and legend are femdem-plot's, as in every other figure.

use std::path::Path;

use anyhow::Result;
use plotters::prelude::*;

use super::Row;
use super::setting::Knob;
use crate::validate::plot::err;
use femdem_plot::{register_font, series_colour};

/// Errors below this are drawn at it (the anchor's is zero by definition).
pub const FLOOR: f64 = 1.0e-4;

/// Draws `rows` (with `front`, indices into `rows` by increasing wall time)
/// into the PNG `path`. Runs that did not pass their peak (the error is a
/// lower bound) are hollow; the front's runs and the anchor are labelled.
pub fn draw(path: &Path, title: &str, rows: &[Row], front: &[usize]) -> Result<()> {
    register_font();
    let root = BitMapBackend::new(path, (1000, 680)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let walls = rows.iter().map(|r| r.wall);
    let (w0, w1) = walls.fold((f64::INFINITY, 0.0_f64), |(a, b), w| (a.min(w), b.max(w)));
    let e1 = rows.iter().map(|r| r.error.max(FLOOR)).fold(FLOOR, f64::max);
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((0.7 * w0..1.4 * w1).log_scale(), (0.5 * FLOOR..2.0 * e1).log_scale())
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("wall time, s (2 cores)")
        .y_desc("|peak − anchor peak| / anchor peak")
        .x_labels(8)
        .x_label_formatter(&|x| format!("{x:.0}"))
        .label_style(("sans-serif", 15))
        .draw()
        .map_err(err)?;
    let at = |r: &Row| (r.wall, r.error.max(FLOOR));
    let line: Vec<(f64, f64)> = front.iter().map(|&i| at(&rows[i])).collect();
    chart
        .draw_series(LineSeries::new(line, BLACK.stroke_width(2)))
        .map_err(err)?
        .label("Pareto front")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
    let mut knobs: Vec<Knob> = rows.iter().map(|r| r.knob).collect();
    knobs.sort();
    knobs.dedup();
    for knob in knobs {
        let c = series_colour(knob as usize);
        let style = |r: &Row| if r.passed_peak { c.filled() } else { c.stroke_width(2) };
        chart
            .draw_series(rows.iter().filter(|r| r.knob == knob).map(|r| Circle::new(at(r), 5, style(r))))
            .map_err(err)?
            .label(knob.name())
            .legend(move |(x, y)| Circle::new((x + 10, y), 5, c.filled()));
    }
    let labelled = rows.iter().enumerate().filter(|(i, r)| r.anchor || front.contains(i)).map(|(_, r)| r);
    chart
        .draw_series(labelled.map(|r| {
            let label = if r.anchor { format!("{} (anchor)", r.setting.key()) } else { r.setting.key() };
            Text::new(label, at(r), ("sans-serif", 12).into_font().color(&BLACK.mix(0.75)))
        }))
        .map_err(err)?;
    femdem_plot::legend_box(&mut chart, SeriesLabelPosition::UpperRight, 14).map_err(err)?;
    root.present().map_err(err)?;
    Ok(())
}
