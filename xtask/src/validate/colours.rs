//! The colours the validation's figures give the failure modes (the codes
//! of `femdem_post::failures::FailureMode`, 0 for a pre-existing face).

use plotters::style::RGBColor;

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
