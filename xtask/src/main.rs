//! `cargo xtask <task>`: project automation that needs nothing but cargo.
//!
//! - `validate [--profile quick|paper] [--case NAME] [--rates LIST] [--ramp S] [--end-time S] [--mesh M] [--weibull M] [--disc D] [--out DIR] [--sensitivity | --strain-axis | --crushing-onset]`: runs the
//!   reference paper's examples and reports against its numbers
//!   (`docs/validation.md`).
//! - `tradeoff [--quick] [--out DIR]`: the speed–accuracy trade of the
//!   Brazilian disc, measured over its knobs (`docs/tradeoff.md`).
//! - `bench [--memory | --callgrind | --paper] [-- criterion args…]`: the criterion
//!   benchmarks; with `--memory` only the peak-memory run of joint insertion
//!   on 10⁶ tets; with `--callgrind` the instructions per tet-step of each
//!   kernel of the step (needs valgrind; `docs/performance.md`).
//! - `map [--seed N] [--out FILE] [--width W] [--height H] [--clearance C]`:
//!   a seeded layered fracture map in the trace-file format (`map.rs`).
//! - `fixtures`: regenerates the Gmsh test fixtures (ASCII and binary) and
//!   the paper cases' meshes (needs `pip install gmsh`).

mod bench;
mod fixtures;
mod map;
mod tradeoff;
mod validate;

use anyhow::{Result, bail};
use clap::Parser;

/// femdem's project tasks (`cargo xtask TASK --help` for each).
#[derive(Parser)]
#[command(name = "cargo xtask", bin_name = "cargo xtask", version, about)]
enum Task {
    /// Run the paper's examples through `femdem run`, check them against
    /// the paper and closed forms, and write a report.
    Validate(validate::Args),
    /// Measure the speed–accuracy trade of the case file's knobs.
    Tradeoff(tradeoff::Args),
    /// The criterion benchmarks (arguments after `--` go to criterion).
    Bench(bench::Args),
    /// Regenerate the Gmsh test fixtures and the paper cases' meshes (needs
    /// `pip install gmsh`).
    Fixtures,
    /// Write a layered fracture map (a trace file).
    Map(map::Args),
}

fn main() -> Result<()> {
    match Task::parse() {
        Task::Bench(args) => bench::run(args),
        Task::Fixtures => fixtures::run(),
        Task::Map(args) => map::run(args),
        Task::Validate(args) => validate::run(args),
        Task::Tradeoff(args) => tradeoff::run(args),
    }
}

/// The workspace root: the parent of this crate's directory where it was
/// built, or else the current directory when that holds the workspace (a
/// prebuilt xtask binary run in a copy of the repository elsewhere).
pub fn root() -> std::path::PathBuf {
    let built = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("xtask lives in the workspace");
    let is_workspace = |p: &std::path::Path| p.join("xtask").join("Cargo.toml").is_file();
    if !is_workspace(built)
        && let Ok(cwd) = std::env::current_dir()
        && is_workspace(&cwd)
    {
        return cwd;
    }
    built.to_path_buf()
}

/// Runs a command in the workspace root, failing on a non-zero exit.
pub fn run_in_root(cmd: &mut std::process::Command) -> Result<()> {
    let status = cmd.current_dir(root()).status()?;
    if !status.success() {
        bail!("{cmd:?} failed with {status}");
    }
    Ok(())
}
