//! `cargo xtask <task>`: project automation that needs nothing but cargo.
//!
//! - `validate [--profile quick|paper] [--case NAME] [--rates LIST] [--ramp S] [--end-time S] [--out DIR] [--sensitivity]`: runs the
//!   reference paper's examples and reports against its numbers
//!   (`docs/validation.md`).
//! - `tradeoff [--quick] [--out DIR]`: the speed–accuracy trade of the
//!   Brazilian disc, measured over its knobs (`docs/tradeoff.md`).
//! - `bench [--memory | --callgrind] [criterion args…]`: the criterion
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

fn main() -> Result<()> {
    let mut args = std::env::args().skip(1);
    let task = args.next();
    let rest: Vec<String> = args.collect();
    match task.as_deref() {
        Some("bench") => bench::run(&rest),
        Some("fixtures") => fixtures::run(),
        Some("map") => map::run(&rest),
        Some("validate") => validate::run(&rest),
        Some("tradeoff") => tradeoff::run(&rest),
        Some(other) => bail!("unknown task `{other}`; tasks: validate, tradeoff, bench, fixtures, map"),
        None => bail!("usage: cargo xtask <validate|tradeoff|bench|fixtures|map>"),
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
