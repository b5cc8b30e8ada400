//! What one Brazilian run measured, with the run it came from: the
//! measurement itself (the load–strain curve and its peak, Eq. 21–23, the
//! energy account, where and how joints failed) is
//! `femdem_post::brazilian::Measured`, which this derefs to.

use std::ops::Deref;

use anyhow::Result;
use femdem_post::brazilian::Measured;
pub use femdem_post::brazilian::{BAND, DROP};

use super::case::Disc;
use crate::validate::runner::RunOutput;

/// The measured outcome of one run, with its files.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The run's files.
    pub run: RunOutput,
    /// What it measured.
    pub measured: Measured,
}

impl Outcome {
    /// ε_yy of the first history row at or after time `t`, if any.
    pub fn strain_at_time(&self, t: f64) -> Option<f64> {
        self.time.iter().position(|&x| x >= t).map(|i| self.curve[i].0)
    }

    /// Reads a finished run of `disc`.
    pub fn read(run: RunOutput, disc: Disc) -> Result<Outcome> {
        let measured = Measured::read(&run.dir, disc.geometry())?;
        Ok(Outcome { run, measured })
    }
}

impl Deref for Outcome {
    type Target = Measured;

    fn deref(&self) -> &Measured {
        &self.measured
    }
}
