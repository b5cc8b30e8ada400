//! `cargo xtask bench`: the criterion benches; `--memory`, the peak memory
//! of a million-tet joint insertion; `--callgrind`, instructions per
//! tet-step of each kernel of the step ([`callgrind`]).

mod callgrind;

use std::process::Command;

use anyhow::Result;

/// Runs the criterion benches, or the memory run with `--memory`, or the
/// instruction counts with `--callgrind`.
pub fn run(args: &[String]) -> Result<()> {
    if args.iter().any(|a| a == "--callgrind") {
        return callgrind::run();
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
