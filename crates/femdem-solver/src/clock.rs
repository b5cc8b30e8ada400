//! Host wall-clock time of the step by stage, on the CPU or resident on a
//! device (waiting on the device included): where a step's time goes, for
//! the run's summary and the measurement kits. Not part of the results: it
//! varies from run to run and never enters the history or a checkpoint.

use std::time::{Duration, Instant};

/// Time spent in each stage of [`crate::Solver`]'s steps (on a device,
/// stages 1 and 5 run there and their time is the host's wait; with stage 1
/// alone on the device, its uploads and read-backs are in `forces`; the
/// watched list made again when a crack makes tets contactable is in
/// `failures`). Not counted: what runs between steps (the output, the run
/// guard) and, resident, sending a host-side change up before the step (a
/// decree, a restore) with the watched list made again after it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StageTimes {
    /// Steps timed.
    pub steps: u64,
    /// Stage 1 on the device, with its read-back (failure count, the
    /// drives' and watched nodes' state; the stresses on steps that ask
    /// for them), and the host's copy of it.
    pub forces: Duration,
    /// Stage 2: the failures' record (read-backs of the failed joints and
    /// the positions on failure steps).
    pub failures: Duration,
    /// Stage 3 on the host: detection (full or incremental), the newly
    /// allowed pairs, the certificates renewed or anchored (`PassClock`).
    pub detection: Duration,
    /// Stage 3: choosing the pairs to clip and their Eq. 17 contacts on the
    /// device (upload, dispatch, read-back).
    pub geometry: Duration,
    /// Of [`StageTimes::geometry`], the device's part: from sending the
    /// pairs to having their results.
    pub geometry_device: Duration,
    /// Stage 3 on the host: the pair loop (ramps, offsets, friction,
    /// certificates), the sums into the nodes and the list of contact
    /// forces to send down.
    pub pairs: Duration,
    /// Stage 4: the drives' reactions on the host.
    pub drives: Duration,
    /// Stage 5 on the device with its read-back (the sums, the touched
    /// nodes' new state; every node's position and velocity on steps that
    /// ask for stresses or energies: output, history rows, checks).
    pub update: Duration,
    /// Stage 6: the account and the record on the host.
    pub account: Duration,
}

impl StageTimes {
    /// Adds a contact pass's parts: the pass clock's advance from
    /// `before` to `after`.
    pub(crate) fn add_pass(&mut self, before: &PassClock, after: &PassClock) {
        self.detection += after.detection - before.detection;
        self.geometry += after.geometry - before.geometry;
        self.pairs += after.pairs - before.pairs;
    }

    /// The stages' time together (the device's part of the pair geometry
    /// counted once, within it): at most the steps' wall time.
    pub fn total(&self) -> Duration {
        self.forces
            + self.failures
            + self.detection
            + self.geometry
            + self.pairs
            + self.drives
            + self.update
            + self.account
    }

    /// The stages' names and their mean time a step, ms, in step order;
    /// stages that took no time (contact in a scene without it, the
    /// device's part on the CPU) left out.
    pub fn per_step_ms(&self) -> Vec<(&'static str, f64)> {
        let n = self.steps.max(1) as f64;
        let ms = |d: Duration| d.as_secs_f64() * 1e3 / n;
        vec![
            ("forces", ms(self.forces)),
            ("failures", ms(self.failures)),
            ("detection", ms(self.detection)),
            ("pair geometry", ms(self.geometry)),
            ("of which device", ms(self.geometry_device)),
            ("pair loop", ms(self.pairs)),
            ("drives", ms(self.drives)),
            ("update", ms(self.update)),
            ("account", ms(self.account)),
        ]
        .into_iter()
        .filter(|&(_, ms)| ms > 0.0)
        .collect()
    }
}

impl std::ops::AddAssign for StageTimes {
    fn add_assign(&mut self, o: Self) {
        self.steps += o.steps;
        self.forces += o.forces;
        self.failures += o.failures;
        self.detection += o.detection;
        self.geometry += o.geometry;
        self.geometry_device += o.geometry_device;
        self.pairs += o.pairs;
        self.drives += o.drives;
        self.update += o.update;
        self.account += o.account;
    }
}

/// Host wall-clock time of a contact pass (`Contact::pass_with`) by part.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct PassClock {
    /// Resetting the touched nodes, detection (full or incremental), the
    /// newly allowed pairs, the certificates, which pairs were in contact.
    pub detection: Duration,
    /// Choosing the pairs to clip and asking the geometry for them (only
    /// where a geometry computes them elsewhere).
    pub geometry: Duration,
    /// The pair loop, the sums into the nodes and the bookkeeping after.
    pub pairs: Duration,
}

/// The time since `start`, added to `total`; restarts `start`.
pub(crate) fn lap(start: &mut Instant, total: &mut Duration) {
    let now = Instant::now();
    *total += now - *start;
    *start = now;
}
