//! Line charts: named `(x, y)` series on one pair of axes.

use std::path::Path;

use plotters::prelude::*;

use crate::style::{legend_box, padded_range, register_font, series_colour};
use crate::{PlotError, Series, check_png};

/// One chart of line series: its caption, axis labels and size. The y range
/// always includes 0; each series has the next colour of
/// [`series_colour`], a 2 px line and an entry in a framed legend at the
/// top left.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineChart<'a> {
    title: &'a str,
    x_label: &'a str,
    y_label: &'a str,
    size: (u32, u32),
    scaled: bool,
}

impl<'a> LineChart<'a> {
    /// A 900 × 600 px chart with this caption and these axis labels, the
    /// values shown as given.
    pub fn new(title: &'a str, x_label: &'a str, y_label: &'a str) -> Self {
        LineChart { title, x_label, y_label, size: (900, 600), scaled: false }
    }

    /// The same chart `width` × `height` px.
    pub fn size(self, width: u32, height: u32) -> Self {
        LineChart { size: (width, height), ..self }
    }

    /// The same chart with each axis whose largest magnitude lies outside
    /// [0.01, 10⁴) shown in units of a power of ten that is a multiple of 3
    /// (named in the axis label: an SI unit takes its prefix, `time (µs)`,
    /// a quantity with no unit in thousandths per mille, `strain (‰)`,
    /// anything else `(×10ⁿ)`), so that tick labels stay short: SI
    /// histories span 1e-7 s to 1e9 Pa.
    pub fn scaled(self) -> Self {
        LineChart { scaled: true, ..self }
    }

    /// Draws `series` into the PNG file `path` (created or replaced).
    ///
    /// # Errors
    /// A [`PlotError`] naming `path` if it does not end in `.png` or cannot
    /// be written.
    pub fn draw(&self, path: &Path, series: &[Series]) -> Result<(), PlotError> {
        check_png(path)?;
        register_font();
        let finite: Vec<Vec<(f64, f64)>> = series
            .iter()
            .map(|(_, p)| p.iter().copied().filter(|(x, y)| x.is_finite() && y.is_finite()).collect())
            .collect();
        let (x_power, y_power) = if self.scaled {
            (power_of(finite.iter().flatten().map(|p| p.0)), power_of(finite.iter().flatten().map(|p| p.1)))
        } else {
            (0, 0)
        };
        let (sx, sy) = (10f64.powi(-x_power), 10f64.powi(-y_power));
        let scaled: Vec<Vec<(f64, f64)>> =
            finite.iter().map(|p| p.iter().map(|&(x, y)| (x * sx, y * sy)).collect()).collect();
        let (x_label, y_label) = (label(self.x_label, x_power), label(self.y_label, y_power));

        let fail = |e| PlotError::drawing(path, e);
        let root = BitMapBackend::new(path, self.size).into_drawing_area();
        root.fill(&WHITE).map_err(fail)?;
        let xs = padded_range(scaled.iter().flatten().map(|q| q.0));
        let ys = padded_range(scaled.iter().flatten().map(|q| q.1).chain([0.0]));
        let mut chart = ChartBuilder::on(&root)
            .caption(self.title, ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(xs, ys)
            .map_err(fail)?;
        chart.configure_mesh().x_desc(x_label).y_desc(y_label).label_style(("sans-serif", 15)).draw().map_err(fail)?;
        for (i, ((name, _), points)) in series.iter().zip(scaled).enumerate() {
            let c = series_colour(i);
            chart
                .draw_series(LineSeries::new(points, c.stroke_width(2)))
                .map_err(fail)?
                .label(name.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
        }
        if !series.is_empty() {
            legend_box(&mut chart, SeriesLabelPosition::UpperLeft, 15).map_err(fail)?;
        }
        root.present().map_err(fail)?;
        Ok(())
    }
}

/// Draws `series` into the PNG file `path` with the validation's look:
/// [`LineChart::new`]`(title, x_desc, y_desc)`, values as given.
///
/// # Errors
/// As [`LineChart::draw`].
pub fn lines(path: &Path, title: &str, x_desc: &str, y_desc: &str, series: &[Series]) -> Result<(), PlotError> {
    LineChart::new(title, x_desc, y_desc).draw(path, series)
}

/// The power of ten (a multiple of 3) to show `values` in: 0 when their
/// largest magnitude lies in [0.01, 10⁴) or is 0.
fn power_of(values: impl Iterator<Item = f64>) -> i32 {
    let largest = values.map(f64::abs).fold(0.0, f64::max);
    if largest == 0.0 || (0.01..1e4).contains(&largest) {
        return 0;
    }
    3 * (largest.log10() / 3.0).floor() as i32
}

/// SI units a label may end in, `name (unit)`, that take a prefix.
const SI_UNITS: [&str; 7] = ["s", "m", "N", "J", "Pa", "W", "kg"];

/// `text` with the power of ten its axis is shown in, when there is one:
/// a label ending in an SI unit, `time (s)`, takes the prefix
/// (`time (µs)`, `stress (MPa)`); one with no unit shown in thousandths
/// takes per mille (`strain (‰)`); any other, `(×10ⁿ)`.
fn label(text: &str, power: i32) -> String {
    if power == 0 {
        return text.to_owned();
    }
    const PREFIXES: [(i32, &str); 8] =
        [(-12, "p"), (-9, "n"), (-6, "µ"), (-3, "m"), (3, "k"), (6, "M"), (9, "G"), (12, "T")];
    if let Some((name, unit)) = text.strip_suffix(')').and_then(|stem| stem.rsplit_once(" (")) {
        // `kg` already carries a prefix: grams take the new one.
        let (base, shift) = if unit == "kg" { ("g", 3) } else { (unit, 0) };
        let prefix = if power + shift == 0 {
            Some("")
        } else {
            PREFIXES.iter().find(|(p, _)| *p == power + shift).map(|(_, s)| *s)
        };
        if let (true, Some(prefix)) = (SI_UNITS.contains(&unit), prefix) {
            return format!("{name} ({prefix}{base})");
        }
    }
    if power == -3 && !text.ends_with(')') {
        return format!("{text} (‰)");
    }
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut exponent: String =
        power.unsigned_abs().to_string().chars().map(|d| DIGITS[d as usize - '0' as usize]).collect();
    if power < 0 {
        exponent.insert(0, '⁻');
    }
    format!("{text} (×10{exponent})")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axes_outside_plain_magnitudes_are_shown_in_engineering_powers() {
        assert_eq!(power_of([0.0, 5e-5].into_iter()), -6);
        assert_eq!(power_of([0.0012, -0.0001].into_iter()), -3);
        assert_eq!(power_of([2800.0].into_iter()), 0);
        assert_eq!(power_of([-3.2e7].into_iter()), 6);
        assert_eq!(power_of([0.0].into_iter()), 0);
        assert_eq!(power_of([0.01].into_iter()), 0);
        assert_eq!(label("time (s)", -6), "time (µs)");
        assert_eq!(label("time (s)", -3), "time (ms)");
        assert_eq!(label("stress (Pa)", 6), "stress (MPa)");
        assert_eq!(label("load (N)", 3), "load (kN)");
        assert_eq!(label("mass (kg)", -3), "mass (g)");
        assert_eq!(label("strain", -3), "strain (‰)");
        assert_eq!(label("strain", -6), "strain (×10⁻⁶)");
        assert_eq!(label("stress", 12), "stress (×10¹²)");
        assert_eq!(label("count (items)", 3), "count (items) (×10³)");
        assert_eq!(label("time (s)", 15), "time (s) (×10¹⁵)");
        assert_eq!(label("load (N)", 0), "load (N)");
    }

    #[test]
    fn a_name_without_png_is_refused_before_drawing() {
        let path = std::env::temp_dir().join("femdem-plot-refused.svg");
        let err = lines(&path, "t", "x", "y", &[]).unwrap_err();
        assert!(err.to_string().contains("femdem-plot-refused.svg") && err.to_string().contains(".png"), "{err}");
        assert!(!path.exists());
    }

    #[test]
    fn a_chart_is_a_png_of_its_size_even_with_non_finite_points() {
        let path = std::env::temp_dir().join(format!("femdem-plot-size-{}.png", std::process::id()));
        let points = vec![(0.0, 1e-7), (1e-6, f64::NAN), (2e-6, 3e-7), (f64::INFINITY, 0.0)];
        LineChart::new("t", "x", "y").size(640, 480).scaled().draw(&path, &[("a".into(), points)]).unwrap();
        let png = std::fs::read(&path).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        assert_eq!(&png[12..16], b"IHDR");
        let dim = |at: usize| u32::from_be_bytes(png[at..at + 4].try_into().unwrap());
        assert_eq!((dim(16), dim(20)), (640, 480));
        std::fs::remove_file(&path).unwrap();
    }
}
