//! `femdem run CASE.toml [--out DIR] [--overwrite] [--resume [DIR]]`: the
//! run driver of `femdem_run` with a progress bar or plain progress lines
//! on stderr, the driver's notes on stderr, a summary on stdout, and the
//! signals SIGINT, SIGTERM (what cluster schedulers send at a time limit)
//! and SIGHUP turned into its stop flag: the run then writes its state and
//! a checkpoint, and exits with an error that says how to resume.

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use anyhow::{Result, bail};
use femdem_run::{Observer, RunOptions, Status, provenance};

use super::progress::Progress;

/// The terminal as the run's [`Observer`].
struct Terminal {
    progress: Option<Progress>,
    /// `--progress-interval`: wall time between plain progress lines.
    interval: Option<Duration>,
}

impl Observer for Terminal {
    fn note(&mut self, line: &str) {
        eprintln!("femdem: {line}");
    }

    fn started(&mut self, first: u64, total: u64, elements: u64) {
        let mut progress = Progress::new(total, elements).starting_at(first);
        if let Some(interval) = self.interval {
            progress = progress.every(interval);
        }
        self.progress = Some(progress);
    }

    fn stepped(&mut self, steps: u64, time: f64, status: &dyn Fn() -> Status) {
        if let Some(p) = &mut self.progress {
            p.update(steps, time, status);
        }
    }

    fn ended(&mut self) {
        if let Some(p) = &self.progress {
            p.finish();
        }
    }
}

/// Runs the command; `progress_interval` is `--progress-interval`, s.
pub fn run(path: &Path, options: RunOptions, progress_interval: Option<f64>) -> Result<()> {
    let stop = Arc::new(AtomicBool::new(false));
    {
        let stop = stop.clone();
        // A second handler cannot be installed (tests call run twice): then
        // the signal kills as usual.
        let _ = ctrlc::set_handler(move || stop.store(true, Ordering::SeqCst));
    }
    let mut terminal =
        Terminal { progress: None, interval: progress_interval.map(|s| Duration::from_secs_f64(s.max(0.0))) };
    let s = femdem_run::run(path, options, &stop, &mut terminal)?;
    println!(
        "{} after {} steps, t = {:.6e} s",
        if s.interrupted { "interrupted" } else { "finished" },
        s.steps,
        s.time
    );
    if let Some(w) = &s.past_peak {
        println!("ended       past the peak: load {:.6e} N below {} of its peak {:.6e} N", w.last, w.fraction, w.peak);
    }
    println!("wall time   {:.2} s", s.wall);
    println!(
        "throughput  {:.3e} tet-steps/s ({} threads, vector unit {})",
        s.throughput,
        rayon::current_num_threads(),
        s.vector_unit
    );
    if let Some(adapter) = &s.device {
        println!(
            "device      {adapter}; {} bytes a step between host and device (more on output steps)",
            s.device_bytes
        );
    }
    if let Some(times) = &s.stage_times {
        let stages: Vec<String> = times.per_step_ms().iter().map(|(name, ms)| format!("{name} {ms:.3}")).collect();
        println!("stages      ms a step over {} steps (host wall clock): {}", times.steps, stages.join(", "));
        if !s.read_backs.is_empty() && times.steps > 0 {
            let per_step = |seconds: f64| seconds * 1e3 / times.steps as f64;
            let parts: Vec<String> =
                s.read_backs.iter().map(|p| format!("{} {:.3}", p.name(), per_step(p.seconds))).collect();
            println!("read-backs  ms a step (host wall clock, the whole run): {}", parts.join(", "));
        }
    }
    println!("built       femdem {}; {}; simd {}", provenance::build(), provenance::cpu(), provenance::simd());
    println!("results     {}", s.frames.display());
    println!("fractures   {} ({} joints failed)", s.fractures.display(), s.failed_joints);
    println!("history     {}", s.history.display());
    println!("failures    {}", s.failures.display());
    if let Some(file) = &s.checkpoint {
        println!("checkpoint  {}", file.display());
    }
    if s.interrupted {
        bail!(
            "interrupted by a signal (Ctrl-C, SIGTERM or SIGHUP); the state at t = {:.6e} s was written, and a \
             checkpoint to continue from: femdem run {}{} --resume {}",
            s.time,
            path.display(),
            s.overrides.iter().map(|a| format!(" --set '{a}'")).collect::<String>(),
            s.dir.display()
        );
    }
    Ok(())
}
