//! What a Brazilian (diametral compression) run measured: the load–strain
//! curve and its peak, the indirect tensile strength of Eq. 23, the first
//! load drop, the energy account, and where and how joints failed.

use std::path::Path;

use anyhow::Result;

use crate::failures::{Failure, Modes};
use crate::table::Table;

/// The disc's geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Disc {
    /// Diameter D, m.
    pub diameter: f64,
    /// Thickness t, m.
    pub thickness: f64,
}

impl Disc {
    /// The indirect tensile strength of load `f` (N), Eq. 23:
    /// `f_bt = 2F / (π D t)`, Pa; also Hondros' σx at the centre.
    pub fn f_bt(self, f: f64) -> f64 {
        2.0 * f / (std::f64::consts::PI * self.diameter * self.thickness)
    }
}

/// Half-width of the band around the loaded diameter (x = 0) that counts
/// as "on the diameter", m.
pub const BAND: f64 = 5.0e-3;

/// Relative fall of the load that marks a load drop (a crushing event or
/// the split): 5%, well above the few-per-mille ripple of the curves.
pub const DROP: f64 = 0.05;

/// The first local maximum of `load` after which the load falls by more
/// than `drop` of it (ignoring maxima below a tenth of the largest load,
/// the start-up ripple): its row. `None` when the load never drops so far.
pub fn first_drop(load: &[f64], drop: f64) -> Option<usize> {
    let floor = 0.1 * load.iter().copied().fold(0.0, f64::max);
    let mut top = 0;
    for (i, &f) in load.iter().enumerate() {
        if f > load[top] {
            top = i;
        }
        if load[top] > floor && f < (1.0 - drop) * load[top] {
            return Some(top);
        }
    }
    None
}

/// The measured outcome of one Brazilian run, read from its results.
#[derive(Debug, Clone)]
pub struct Measured {
    /// Time of every history row, s.
    pub time: Vec<f64>,
    /// `(ε_yy, F)` of every history row (Eq. 22, Eq. 21).
    pub curve: Vec<(f64, f64)>,
    /// Peak load F, N.
    pub peak: f64,
    /// Time of the peak, s.
    pub peak_time: f64,
    /// Indirect tensile strength of Eq. 23 at the peak, Pa.
    pub f_bt: f64,
    /// Whether the load fell below 90% of the peak afterwards (the peak was
    /// passed, not cut off by the end time).
    pub passed_peak: bool,
    /// The first load drop of [`DROP`] (Eq. 21's F before it, N, and its
    /// time, s): the first crushing event under a platen when that comes
    /// before the split.
    pub first_drop: Option<(f64, f64)>,
    /// Largest |balance| / external work once the work reached 10% of its
    /// final value ([`Table::energy_error`]).
    pub energy_error: f64,
    /// Every joint failure.
    pub failures: Vec<Failure>,
    /// Steps taken.
    pub steps: f64,
}

impl Measured {
    /// Reads the results in `dir` of a run of `disc` whose history has the
    /// `load` and `strain` columns of `[output.load_strain]`.
    ///
    /// # Errors
    /// Unreadable results, a missing column, or a history without rows.
    pub fn read(dir: &Path, disc: Disc) -> Result<Measured> {
        let h = Table::history(dir)?;
        if h.is_empty() {
            anyhow::bail!("{} has no rows", h.path.display());
        }
        let (time, load, strain) = (h.col("time")?, h.col("load")?, h.col("strain")?);
        let energy_error = h.energy_error()?;
        let curve: Vec<(f64, f64)> = strain.iter().copied().zip(load.iter().copied()).collect();
        let (ipk, peak) =
            load.iter().copied().enumerate().fold((0, f64::NEG_INFINITY), |a, (i, f)| if f > a.1 { (i, f) } else { a });
        let passed_peak = load[ipk..].iter().any(|&f| f < 0.9 * peak);
        let failures = Failure::read_all(dir)?;
        let first_drop = first_drop(&load, DROP).map(|i| (load[i], time[i]));
        Ok(Measured {
            first_drop,
            peak_time: time[ipk],
            time,
            curve,
            peak,
            f_bt: disc.f_bt(peak),
            passed_peak,
            energy_error,
            failures,
            steps: h.col("step")?.last().copied().unwrap_or(0.0),
        })
    }

    /// The load F at the history row nearest time `t`, N.
    pub fn load_at(&self, t: f64) -> f64 {
        let i =
            self.time.iter().enumerate().min_by(|a, b| (a.1 - t).abs().total_cmp(&(b.1 - t).abs())).map_or(0, |x| x.0);
        self.curve.get(i).map_or(0.0, |c| c.1)
    }

    /// The first failure, if any.
    pub fn first_failure(&self) -> Option<&Failure> {
        self.failures.iter().min_by(|a, b| a.time.total_cmp(&b.time))
    }

    /// Share of failures within [`BAND`] of the loaded diameter (x = 0).
    pub fn on_diameter(&self) -> f64 {
        let n = self.failures.iter().filter(|f| f.at[0].abs() < BAND).count();
        n as f64 / self.failures.len().max(1) as f64
    }

    /// Modes of the central fracture: on the diameter band and within half
    /// the radius of the centre along it.
    pub fn central(&self, disc: Disc) -> Modes {
        Modes::of(self.failures.iter().filter(|f| f.at[0].abs() < BAND && f.at[1].abs() < 0.25 * disc.diameter))
    }

    /// Modes within [`BAND`] of the top (`+1`) or bottom (`−1`) contact.
    pub fn at_contact(&self, disc: Disc, side: f64) -> Modes {
        let r = 0.5 * disc.diameter;
        Modes::of(self.failures.iter().filter(|f| f.at[1] * side > r - BAND))
    }

    /// All failures by mode.
    pub fn modes(&self) -> Modes {
        Modes::of(self.failures.iter())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_drop_is_the_maximum_before_the_first_fall_of_the_given_size() {
        // Ripple of 2% at 2, a 10% drop after 5, the peak 7 later.
        let load = [0.0, 1.0, 2.0, 1.96, 3.0, 5.0, 4.5, 6.0, 7.0, 1.0];
        assert_eq!(first_drop(&load, 0.05), Some(5));
        assert_eq!(first_drop(&load, 0.2), Some(8));
        assert_eq!(first_drop(&load[..8], 0.2), None);
        // Start-up ripple below a tenth of the largest load is not a drop.
        assert_eq!(first_drop(&[0.0, 0.5, 0.2, 8.0, 9.0, 2.0], 0.05), Some(4));
    }

    #[test]
    fn eq_23_is_two_f_over_pi_d_t() {
        // The paper's disc (D = 40 mm, t = 15 mm) at F = 1,845 N: 1.96 MPa.
        let disc = Disc { diameter: 0.04, thickness: 0.015 };
        assert!((disc.f_bt(1845.0) / 1.9575e6 - 1.0).abs() < 1e-4, "{}", disc.f_bt(1845.0));
    }
}
