//! `[output.load_strain] stop_below_peak`: the rule that ends a run once
//! its load has fallen past the peak.

use femdem_case::setup::LoadStrain;
use femdem_solver::Solver;

/// Watches the load `F` of Eq. 21 step by step and says when a run is
/// over, i.e. once a joint has failed and `F` has fallen below `fraction`
/// of its largest value so far.
pub(crate) struct PeakWatch {
    ls: LoadStrain,
    /// The fraction of the peak that ends the run.
    pub fraction: f64,
    /// The largest load so far, N.
    pub peak: f64,
    /// The load at the last step, N.
    pub last: f64,
}

impl PeakWatch {
    /// A watch, when the case asks for one.
    pub fn new(ls: LoadStrain) -> Option<Self> {
        ls.stop_below_peak.map(|fraction| PeakWatch { ls, fraction, peak: 0.0, last: 0.0 })
    }

    /// Updates the watch with the solver's last record; true once the run
    /// is over.
    pub fn ended(&mut self, solver: &Solver) -> bool {
        let r = solver.record();
        let (load, _) = self.ls.evaluate(&r.drive_forces, &r.drive_displacements);
        self.last = load;
        self.peak = self.peak.max(load);
        !solver.failures().is_empty() && self.peak > 0.0 && load < self.fraction * self.peak
    }
}
