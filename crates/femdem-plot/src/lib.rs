//! femdem's figures, drawn in Rust into PNG files: line charts of named
//! `(x, y)` series (`femdem plot`'s history plots, the validation's
//! load–strain curves and Mohr circles) and maps of flat coloured
//! triangles (the validation's fracture patterns and stress maps).
//!
//! Text is set in the bundled DejaVu Sans (`assets/`, its licence beside
//! it), registered with plotters as `sans-serif` on first use, so nothing
//! depends on the system's fonts or fontconfig.
//!
//! # Code map
//!
//! - [`LineChart`] (`lines.rs`) draws one chart of line series; [`lines`]
//!   is its plain form with the validation's look (900 × 600 px, y range
//!   including 0, legend top left).
//! - [`triangles`] (`triangles.rs`) draws filled triangles in a plane.
//! - `style.rs`: the font ([`register_font`]), the palette
//!   ([`series_colour`]), the diverging map ([`diverging`]) and the
//!   framed legend ([`legend_box`]) every figure shares.
//! - [`PlotError`]: every failure, with the file concerned.
//!
//! **Architecture invariant:** knows plotters and PNG files only: no
//! physics, no case files, no CSV, no terminal. Callers hand it numbers
//! and labels in the units they want shown.
//!
//! # Example
//!
//! ```
//! let path = std::env::temp_dir().join(format!("femdem-plot-doc-{}.png", std::process::id()));
//! let curve: Vec<(f64, f64)> = (0..50).map(|i| (f64::from(i), f64::from(i * i))).collect();
//! femdem_plot::lines(&path, "A parabola", "x", "y", &[("x²".to_owned(), curve)])?;
//! assert!(std::fs::read(&path)?.starts_with(b"\x89PNG\r\n\x1a\n"));
//! std::fs::remove_file(&path)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod lines;
mod style;
mod triangles;

use std::fmt;
use std::path::{Path, PathBuf};

pub use lines::{LineChart, lines};
pub use plotters::style::RGBColor;
pub use style::{diverging, legend_box, register_font, series_colour};
pub use triangles::triangles;

/// One named line: its points `(x, y)` in the order they are joined.
/// Points with a non-finite coordinate are left out.
pub type Series = (String, Vec<(f64, f64)>);

/// A figure could not be drawn or written.
#[derive(Debug, Clone, PartialEq)]
pub struct PlotError {
    /// The PNG file being drawn.
    pub path: PathBuf,
    /// What went wrong (plotters' or the PNG encoder's message).
    pub message: String,
}

impl PlotError {
    /// An error drawing `path`, from plotters' error `e`.
    pub fn drawing<E: fmt::Debug>(path: &Path, e: E) -> PlotError {
        PlotError { path: path.to_owned(), message: format!("{e:?}") }
    }
}

impl fmt::Display for PlotError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "drawing the figure {}: {}", self.path.display(), self.message)
    }
}

impl std::error::Error for PlotError {}

/// Fails unless `path` names a `.png` file (the only format written; the
/// encoder picks it by the extension).
fn check_png(path: &Path) -> Result<(), PlotError> {
    if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("png")) {
        Ok(())
    } else {
        Err(PlotError { path: path.to_owned(), message: "figures are PNG files: the name must end in .png".into() })
    }
}
