//! Progress reporting: a bar on a terminal, periodic plain lines otherwise.
//! Both show the steps, the simulated time, the joints failed so far, the
//! load `F` of Eq. 21 where `[output.load_strain]` defines it, and the
//! element-steps per second.

use std::io::IsTerminal;
use std::time::{Duration, Instant};

use femdem_run::Status;
use indicatif::{ProgressBar, ProgressStyle};

/// Seconds between plain progress lines when stderr is not a terminal.
const PLAIN_INTERVAL: Duration = Duration::from_secs(10);

/// `"12 joints failed  load 2.512e3 N"`.
fn status_text(status: &Status) -> String {
    let joints = if status.failed_joints == 1 { "joint" } else { "joints" };
    let mut s = format!("{} {joints} failed", status.failed_joints);
    if let Some(load) = status.load {
        s.push_str(&format!("  load {load:.4e} N"));
    }
    s
}

/// Reports steps, simulated time, failures, load, element-steps per
/// second and ETA.
pub struct Progress {
    bar: Option<ProgressBar>,
    start: Instant,
    last_line: Instant,
    /// Time between plain lines.
    interval: Duration,
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
        Progress { bar, start: now, last_line: now, interval: PLAIN_INTERVAL, total, elements, first: 0 }
    }

    /// The same reporter for a run that starts at step `first` (a resumed
    /// one): rates count the steps from there.
    pub fn starting_at(self, first: u64) -> Progress {
        Progress { first, ..self }
    }

    /// The same reporter writing a plain line every `interval` (instead of
    /// every 10 s) when stderr is not a terminal.
    pub fn every(self, interval: Duration) -> Progress {
        Progress { interval, ..self }
    }

    /// Element-steps per second so far, `steps` being the steps done
    /// since step 0.
    pub fn throughput(&self, steps: u64) -> f64 {
        steps.saturating_sub(self.first) as f64 * self.elements as f64 / self.start.elapsed().as_secs_f64().max(1e-9)
    }

    /// Reports that `steps` steps are done at simulated time `time`;
    /// `status` is asked for only when a report is due.
    pub fn update(&mut self, steps: u64, time: f64, status: &dyn Fn() -> Status) {
        if let Some(b) = &self.bar {
            if steps.is_multiple_of(64) || steps == self.total {
                b.set_position(steps);
                b.set_message(format!(
                    "{time:.4e} s  {}  {:.2e} el-steps/s",
                    status_text(&status()),
                    self.throughput(steps)
                ));
            }
        } else if self.last_line.elapsed() >= self.interval {
            self.last_line = Instant::now();
            let rate = steps.saturating_sub(self.first) as f64 / self.start.elapsed().as_secs_f64().max(1e-9);
            let eta = (self.total - steps) as f64 / rate.max(1e-9);
            eprintln!("{}", plain_line(steps, self.total, time, &status(), self.throughput(steps), eta));
        }
    }

    /// Removes the bar.
    pub fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}

/// One plain progress line.
fn plain_line(steps: u64, total: u64, time: f64, status: &Status, throughput: f64, eta: f64) -> String {
    format!(
        "step {steps}/{total}  t = {time:.4e} s  {}  {throughput:.3e} element-steps/s  eta {eta:.0} s",
        status_text(status)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plain_line_carries_the_failed_joints_and_the_load_where_defined() {
        let with_load = Status { failed_joints: 12, load: Some(2512.3) };
        assert_eq!(
            plain_line(100, 200, 1.5e-5, &with_load, 1.2e6, 3.0),
            "step 100/200  t = 1.5000e-5 s  12 joints failed  load 2.5123e3 N  1.200e6 element-steps/s  eta 3 s"
        );
        let without = Status { failed_joints: 1, load: None };
        assert_eq!(
            plain_line(5, 10, 0.0, &without, 0.0, 0.0),
            "step 5/10  t = 0.0000e0 s  1 joint failed  0.000e0 element-steps/s  eta 0 s"
        );
    }
}
