//! What one step reports: the state of step `n` as the step computed it.

use std::ops::Range;

use femdem_core::{Real, Vec3};
use femdem_fracture::FailureMode;

use crate::state::Energies;

/// Joint failures so far, by mode.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct FailureCounts {
    /// Failed by opening (see `femdem_fracture::FailureMode`).
    pub tensile: usize,
    /// Failed by slip.
    pub shear: usize,
    /// Failed with both directions contributing (Eq. 13's combined damage).
    pub mixed: usize,
    /// Failed because the mid-plane collapsed.
    pub collapsed: usize,
}

impl FailureCounts {
    /// Counts one more failure of `mode`.
    pub fn add(&mut self, mode: FailureMode) {
        match mode {
            FailureMode::Tensile => self.tensile += 1,
            FailureMode::Shear => self.shear += 1,
            FailureMode::Mixed => self.mixed += 1,
            FailureMode::Collapsed => self.collapsed += 1,
        }
    }

    /// All failures.
    pub fn total(&self) -> usize {
        self.tensile + self.shear + self.mixed + self.collapsed
    }
}

/// The record of step `n`, everything at time `t_n` (the step evaluates
/// forces at `x_n` and then moves the nodes to `x_{n+1}`; what it reports
/// belongs to `t_n`).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StepRecord {
    /// Step number `n`.
    pub step: u64,
    /// Time `t_n`, s.
    pub time: Real,
    /// Reaction force of each velocity drive (in [`crate::Loads::drives`]
    /// order), N: what the drive had to apply to impose its velocity.
    pub drive_forces: Vec<Vec3>,
    /// Mean displacement `x_n − x_0` of each drive's nodes, m (Δa of
    /// Eq. 22 for a platen).
    pub drive_displacements: Vec<Vec3>,
    /// Work done by each drive's reaction from the start to `t_n`, J,
    /// booked as the external work is (the trapezoidal rule centred on
    /// `t_n`, module documentation of `step`): `Σ r · v` over the drive's
    /// prescribed components, half steps against `v_{n−½}` and the target
    /// `v_{n+½}`. Zero while a drive has not started, and at a static start
    /// (a drive held from the start cannot be displaced).
    pub drive_work: Vec<Real>,
    /// Total force of each surface load (in [`crate::Loads::surfaces`]
    /// order), N.
    pub surface_forces: Vec<Vec3>,
    /// Work done by each surface load from the start to `t_n`, J, booked
    /// as the external work is (the trapezoidal rule centred on `t_n`,
    /// module documentation of `step`): with the drives' work
    /// ([`StepRecord::drive_work`]) it is the external work less gravity's,
    /// a static start's beyond the loads' shares and the kicks' (the
    /// ledger's sum, `crate::ledger`). After a static start
    /// ([`crate::Solver::start_displaced`]) each starts at its Clapeyron
    /// share `½ f_k · u` of the stored energy that the external work
    /// starts at, so the sum agrees with it as far as the static state is
    /// linear elastic.
    pub surface_work: Vec<Real>,
    /// The joints that failed in this step: indices into
    /// [`crate::Solver::failures`].
    pub new_failures: Range<usize>,
    /// Failures since the start, by mode.
    pub failures: FailureCounts,
    /// The energy account after this step.
    pub energies: Energies,
    /// Whether the state terms of [`StepRecord::energies`] (kinetic,
    /// elastic, fracture) were evaluated at this step ([`crate::Want::energy`]);
    /// otherwise they are those of the last step that was asked.
    pub energies_current: bool,
    /// Contact pairs that exerted a force in this step (0 with contact off).
    pub contact_pairs: usize,
}
