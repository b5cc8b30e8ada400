//! `cargo xtask bench`: the criterion benches; `--memory`, the peak memory
//! of a million-tet joint insertion; `--callgrind`, instructions per
//! tet-step of each kernel of the step ([`callgrind`]); `--paper`, the
//! multi-layer case at the paper's mesh size with contact on every
//! pre-existing fracture ([`paper`]).

mod callgrind;
mod paper;

use std::process::Command;

use anyhow::Result;

/// Runs the criterion benches, or the memory run with `--memory`, the
/// instruction counts with `--callgrind`, or the paper-size multi-layer
/// run with `--paper`.
pub fn run(args: &[String]) -> Result<()> {
    if args.iter().any(|a| a == "--callgrind") {
        return callgrind::run();
    }
    if args.iter().any(|a| a == "--paper") {
        return paper::run(args);
    }
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    if args.iter().any(|a| a == "--memory") {
        return crate::run_in_root(Command::new(&cargo).args([
            "run",
            "--release",
            "-p",
            "femdem-benches",
            "--example",
            "joint_memory",
            "--",
            "1000000",
        ]));
    }
    crate::run_in_root(Command::new(&cargo).args(["bench", "-p", "femdem-benches", "--"]).args(args))
}
