//! Progress reporting: a bar on a terminal, periodic plain lines otherwise.

use std::io::IsTerminal;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};

/// Seconds between plain progress lines when stderr is not a terminal.
const PLAIN_INTERVAL: Duration = Duration::from_secs(10);

/// Reports steps, simulated time, element-steps per second and ETA.
pub struct Progress {
    bar: Option<ProgressBar>,
    start: Instant,
    last_line: Instant,
    total: u64,
    elements: u64,
    /// The step this run started from (not 0 after `--resume`).
    first: u64,
}

impl Progress {
    /// A reporter for `total` steps of a model with `elements` evaluated
    /// elements (deformable tets) per step.
    pub fn new(total: u64, elements: u64) -> Progress {
        let bar = std::io::stderr().is_terminal().then(|| {
            let b = ProgressBar::new(total);
            b.set_style(
                ProgressStyle::with_template("{bar:30} {pos}/{len} steps  t = {msg}  eta {eta}")
                    .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            b
        });
        let now = Instant::now();
        Progress { bar, start: now, last_line: now, total, elements, first: 0 }
    }

    /// The same reporter for a run that starts at step `first` (a resumed
    /// one): rates count the steps from there.
    pub fn starting_at(self, first: u64) -> Progress {
        Progress { first, ..self }
    }

    /// Element-steps per second so far, `steps` being the steps done
    /// since step 0.
    pub fn throughput(&self, steps: u64) -> f64 {
        steps.saturating_sub(self.first) as f64 * self.elements as f64 / self.start.elapsed().as_secs_f64().max(1e-9)
    }

    /// Reports that `steps` steps are done at simulated time `time`.
    pub fn update(&mut self, steps: u64, time: f64) {
        if let Some(b) = &self.bar {
            if steps % 64 == 0 || steps == self.total {
                b.set_position(steps);
                b.set_message(format!("{time:.4e} s  {:.2e} el-steps/s", self.throughput(steps)));
            }
        } else if self.last_line.elapsed() >= PLAIN_INTERVAL {
            self.last_line = Instant::now();
            let rate = steps.saturating_sub(self.first) as f64 / self.start.elapsed().as_secs_f64().max(1e-9);
            let eta = (self.total - steps) as f64 / rate.max(1e-9);
            eprintln!(
                "step {steps}/{}  t = {time:.4e} s  {:.3e} element-steps/s  eta {eta:.0} s",
                self.total,
                self.throughput(steps)
            );
        }
    }

    /// Removes the bar.
    pub fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }

    /// Wall time since the start.
    pub fn elapsed(&self) -> Duration {
        self.start.elapsed()
    }
}
