//! Joint failures as `femdem run` records them in `failures.csv`: one row
//! per failed joint, with the centroid of its mid-plane, its area and its
//! mode, typed as the solver classifies it
//! ([`femdem_fracture::FailureMode`]).

use std::path::Path;

use anyhow::{Context, Result};
pub use femdem_fracture::FailureMode;

use crate::table::Table;

/// One row of `failures.csv`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Failure {
    /// Start of the step that broke the joint, s.
    pub time: f64,
    /// The joint's index in the model.
    pub joint: u32,
    /// Centroid of the joint's mid-plane, m.
    pub at: [f64; 3],
    /// The joint's area, m².
    pub area: f64,
    /// How it failed.
    pub mode: FailureMode,
}

impl Failure {
    /// Every row of `dir/failures.csv`, in the order written (by time).
    ///
    /// # Errors
    /// An unreadable or malformed file, or a mode code that is not one of
    /// [`FailureMode`]'s (named by file and row).
    pub fn read_all(dir: &Path) -> Result<Vec<Failure>> {
        let f = Table::read(&dir.join("failures.csv"))?;
        let i = |c: &str| f.index(c);
        let (t, j, x, y, z, a, m) = (i("time")?, i("joint")?, i("x")?, i("y")?, i("z")?, i("area")?, i("mode")?);
        f.rows
            .iter()
            .enumerate()
            .map(|(i, r)| {
                let mode = FailureMode::from_code(r[m] as u8)
                    .filter(|_| r[m].fract() == 0.0)
                    .with_context(|| format!("{}: row {}: mode {} is not 1-4", f.path.display(), i + 1, r[m]))?;
                let joint = Some(r[j])
                    .filter(|v| v.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(v))
                    .with_context(|| format!("{}: row {}: joint {} is not an index", f.path.display(), i + 1, r[j]))?;
                Ok(Failure { time: r[t], joint: joint as u32, at: [r[x], r[y], r[z]], area: r[a], mode })
            })
            .collect()
    }
}

/// Counts of failures by mode.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Modes {
    /// Tensile, shear, mixed, collapsed.
    pub counts: [usize; 4],
}

/// The modes in the order of [`Modes::counts`].
pub const MODES: [FailureMode; 4] =
    [FailureMode::Tensile, FailureMode::Shear, FailureMode::Mixed, FailureMode::Collapsed];

impl Modes {
    /// Counts the failures `f` by mode.
    pub fn of<'a>(f: impl Iterator<Item = &'a Failure>) -> Modes {
        let mut m = Modes::default();
        for x in f {
            m.counts[usize::from(x.mode.code()) - 1] += 1;
        }
        m
    }

    /// All counted failures.
    pub fn total(&self) -> usize {
        self.counts.iter().sum()
    }

    /// How many failed in `mode`.
    pub fn count(&self, mode: FailureMode) -> usize {
        self.counts[usize::from(mode.code()) - 1]
    }

    /// Share of `mode` among all counted failures (0 when there is none).
    pub fn share(&self, mode: FailureMode) -> f64 {
        self.count(mode) as f64 / self.total().max(1) as f64
    }

    /// `T/S/M/C` counts as text.
    pub fn text(&self) -> String {
        let [t, s, m, c] = self.counts;
        format!("T {t} / S {s} / M {m} / C {c}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failures_are_read_with_their_modes_typed_and_a_bad_code_is_refused() {
        let dir = std::env::temp_dir().join(format!("femdem-post-failures-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let header = "time,joint,x,y,z,area,mode\n";
        std::fs::write(dir.join("failures.csv"), format!("{header}1e-6,7,0.1,0.2,0.3,2e-6,1\n2e-6,9,0,0,0,1e-6,2\n"))
            .unwrap();
        let f = Failure::read_all(&dir).unwrap();
        assert_eq!(f.len(), 2);
        assert_eq!((f[0].joint, f[0].mode, f[0].at), (7, FailureMode::Tensile, [0.1, 0.2, 0.3]));
        assert_eq!(f[1].mode, FailureMode::Shear);
        let m = Modes::of(f.iter());
        assert_eq!((m.total(), m.count(FailureMode::Shear), m.share(FailureMode::Tensile)), (2, 1, 0.5));
        assert_eq!(m.text(), "T 1 / S 1 / M 0 / C 0");
        std::fs::write(dir.join("failures.csv"), format!("{header}1e-6,7,0,0,0,1e-6,5\n")).unwrap();
        let err = Failure::read_all(&dir).unwrap_err().to_string();
        assert!(err.contains("row 1: mode 5 is not 1-4"), "{err}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
