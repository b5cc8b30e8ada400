//! `cargo xtask bench`: the criterion benches; `--memory`, the peak memory
//! of a million-tet joint insertion; `--callgrind`, instructions per
//! tet-step of each kernel of the step ([`callgrind`]); `--paper`, the
//! multi-layer case at the paper's mesh size with contact on every
//! pre-existing fracture ([`paper`]).

mod callgrind;
mod paper;

use std::process::Command;

use anyhow::Result;

/// `cargo xtask bench`'s arguments.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Only the peak-memory run of joint insertion on 10⁶ tets.
    #[arg(long, conflicts_with_all = ["callgrind", "paper"])]
    memory: bool,
    /// The instructions per tet-step of each kernel of the step (needs
    /// valgrind).
    #[arg(long, conflicts_with = "paper")]
    callgrind: bool,
    /// The multi-layer case at the paper's size, from a prepared state.
    #[arg(long)]
    paper: bool,
    /// `--paper`: worker threads (default 2).
    #[arg(long, requires = "paper")]
    threads: Option<String>,
    /// `--paper`: the element size, m (default 0.024).
    #[arg(long, requires = "paper")]
    size: Option<String>,
    /// Arguments for criterion (after `--`), e.g. a benchmark filter.
    #[arg(last = true)]
    criterion: Vec<String>,
}

/// Runs the criterion benches, or the memory run with `--memory`, the
/// instruction counts with `--callgrind`, or the paper-size multi-layer
/// run with `--paper`.
pub fn run(args: Args) -> Result<()> {
    if args.callgrind {
        return callgrind::run();
    }
    if args.paper {
        return paper::run(args.threads.as_deref().unwrap_or("2"), args.size.as_deref().unwrap_or("0.024"));
    }
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    if args.memory {
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
    crate::run_in_root(Command::new(&cargo).args(["bench", "-p", "femdem-benches", "--"]).args(&args.criterion))
}
