//! What every figure shares: the bundled font, the palette, the diverging
//! colour map and the framed legend.

use std::ops::Range;
use std::sync::Once;

use plotters::coord::CoordTranslate;
use plotters::prelude::*;
use plotters::style::FontStyle;

/// DejaVu Sans, as Debian packages it (`assets/DejaVuSans.LICENSE`).
const FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// Registers the bundled DejaVu Sans as plotters' `sans-serif` (once per
/// process). Every drawing function here calls it; a caller drawing with
/// plotters directly calls it first (without a registered font, plotters
/// panics on the first text).
pub fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        plotters::style::register_font("sans-serif", FontStyle::Normal, FONT)
            .unwrap_or_else(|_| panic!("the bundled DejaVuSans.ttf is not a font"));
    });
}

/// A qualitative colour for series `i` (eight, then they repeat).
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

/// Draws the legend of `chart`'s labelled series in a framed box at `at`,
/// its text `font_size` px.
pub fn legend_box<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    at: SeriesLabelPosition,
    font_size: u32,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    chart
        .configure_series_labels()
        .position(at)
        .label_font(("sans-serif", font_size))
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()
}

/// The range of the finite `values` padded by 5% of its width on each
/// side; `0..1` when there is none. A range of one value (a constant
/// series) is widened by 5% of it, or by 0.5 around 0, so that it is never
/// empty.
pub(crate) fn padded_range(values: impl Iterator<Item = f64>) -> Range<f64> {
    let (lo, hi) =
        values.filter(|v| v.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    if !lo.is_finite() || !hi.is_finite() {
        return 0.0..1.0;
    }
    let width = hi - lo;
    let pad = if width > 1e-12 * hi.abs().max(lo.abs()) {
        0.05 * width
    } else if hi != 0.0 {
        0.05 * hi.abs()
    } else {
        0.5
    };
    (lo - pad)..(hi + pad)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_padded_range_skips_non_finite_values_and_is_never_empty() {
        let r = padded_range([0.0, f64::NAN, 10.0, f64::INFINITY].into_iter());
        assert!((r.start + 0.5).abs() < 1e-12 && (r.end - 10.5).abs() < 1e-12, "{r:?}");
        assert_eq!(padded_range(std::iter::empty()), 0.0..1.0);
        let one = padded_range([2.0].into_iter());
        assert!((one.start - 1.9).abs() < 1e-12 && (one.end - 2.1).abs() < 1e-12, "{one:?}");
        assert_eq!(padded_range([0.0, 0.0].into_iter()), -0.5..0.5);
    }

    #[test]
    fn the_diverging_map_is_white_at_zero_and_clamped() {
        assert_eq!(diverging(0.0), RGBColor(255, 255, 255));
        assert_eq!(diverging(1.0), RGBColor(178, 24, 43));
        assert_eq!(diverging(7.0), diverging(1.0));
        assert_eq!(diverging(-1.0), RGBColor(33, 102, 172));
    }

    #[test]
    fn the_palette_repeats_after_eight_colours() {
        assert_eq!(series_colour(8), series_colour(0));
        assert_ne!(series_colour(1), series_colour(0));
    }
}
