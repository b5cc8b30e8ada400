//! Another program driving femdem without its command line: load a bundled
//! case, run it through the run driver, then read its peak load and its
//! fragments back with the results library.
//!
//! ```text
//! cargo run --release -p femdem-run --example peak_load [CASE.toml [OUT_DIR]]
//! ```
//!
//! Default: the README's Brazilian disc (`cases/brazilian-split.toml`, about
//! 10 s on 2 cores) into `out/example-peak-load`. The case needs
//! `[output.load_strain]` for its load column.

use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

use anyhow::{Context, Result};
use femdem_post::failures::{Failure, Modes};
use femdem_post::table::Table;

/// Prints the driver's notes, and a line every 10% of the steps.
struct Log {
    total: u64,
    next: u64,
}

impl femdem_run::Observer for Log {
    fn note(&mut self, line: &str) {
        eprintln!("peak_load: {line}");
    }

    fn started(&mut self, first: u64, total: u64, _elements: u64) {
        (self.total, self.next) = (total, first);
    }

    fn stepped(&mut self, steps: u64, time: f64, status: &dyn Fn() -> femdem_run::Status) {
        if steps >= self.next {
            self.next = steps + self.total.div_ceil(10);
            let s = status();
            eprintln!("peak_load: step {steps}/{}, t = {time:.3e} s, {} joints failed", self.total, s.failed_joints);
        }
    }
}

fn main() -> Result<()> {
    let mut args = std::env::args_os().skip(1);
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let case = args.next().map_or_else(|| root.join("cases/brazilian-split.toml"), PathBuf::from);
    let out = args.next().map_or_else(|| root.join("out/example-peak-load"), PathBuf::from);

    let options = femdem_run::RunOptions { out: Some(out.clone()), overwrite: true, ..Default::default() };
    let summary = femdem_run::run(&case, options, &AtomicBool::new(false), &mut Log { total: 0, next: 0 })?;

    let history = Table::history(&summary.dir)?;
    let (time, load) = (history.col("time")?, history.col("load").context("the case records no load")?);
    anyhow::ensure!(!load.is_empty(), "{} has no rows", history.path.display());
    let (at, peak) =
        load.iter().enumerate().fold((0, f64::NEG_INFINITY), |a, (i, &f)| if f > a.1 { (i, f) } else { a });
    let failures = Failure::read_all(&summary.dir)?;
    println!("case        {}", case.display());
    println!("steps       {} to t = {:.4e} s ({:.2e} tet-steps/s)", summary.steps, summary.time, summary.throughput);
    println!("peak load   {peak:.1} N at t = {:.4e} s", time[at]);
    println!("failures    {} ({})", failures.len(), Modes::of(failures.iter()).text());

    // The fragments: the case's jointed mesh, rebuilt by the case library,
    // less the joints that failed.
    let loaded = femdem_case::load(&case, &[])?;
    let (_, _, jointed) = femdem_case::prepare::jointed(&loaded)?;
    let pieces = femdem_post::fragments::breakable_fragments(&jointed, &failures)?;
    let total: f64 = pieces.iter().map(|f| f.volume).sum();
    let largest = pieces.first().map_or(0.0, |f| 100.0 * f.volume / total);
    println!("fragments   {} (the largest {largest:.1}% of the breakable volume)", pieces.len());
    println!("results     {}", summary.dir.display());
    Ok(())
}
