//! `cargo xtask bench --callgrind`: instructions per tet-step of each
//! kernel of the explicit step, counted by valgrind's callgrind (repeatable
//! on a loaded machine, unlike wall-clock time; see `docs/performance.md`).
//!
//! Runs `benches/examples/step_profile` (the 3 mm disc with joints) on one
//! rayon thread under callgrind for 5 and for 25 steps and divides the
//! difference of each kernel's inclusive count by the 20 steps' tet-steps,
//! so that the set-up (meshing, the stable-step estimate) cancels out.

use std::path::Path;
use std::process::Command;

use anyhow::{Context, Result, bail};

/// The named per-chunk kernels, as the profile names them.
const KERNELS: [(&str, &str); 4] = [
    ("joints", "femdem_solver::forces::joint_chunk"),
    ("tets", "femdem_solver::forces::tet_chunk"),
    ("gather", "femdem_solver::forces::gather_chunk"),
    ("update", "femdem_solver::step::update::advance_chunk"),
];

const STEPS: [u64; 2] = [5, 25];

/// Builds the example, profiles it twice and prints the table.
pub fn run() -> Result<()> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    crate::run_in_root(Command::new(&cargo).args([
        "build",
        "--release",
        "-p",
        "femdem-benches",
        "--example",
        "step_profile",
    ]))?;
    let target = std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| crate::root().join("target"), Into::into);
    let exe = target.join("release/examples/step_profile");
    let dir = target.join("callgrind");
    std::fs::create_dir_all(&dir)?;
    let mut counts = Vec::new();
    let mut tets = 0;
    for steps in STEPS {
        let out = dir.join(format!("step_profile_{steps}.out"));
        let run = Command::new("valgrind")
            .args(["--tool=callgrind", &format!("--callgrind-out-file={}", out.display())])
            .arg(&exe)
            .args(["3.0", &steps.to_string()])
            .env("RAYON_NUM_THREADS", "1")
            .output()
            .context("running valgrind (Debian package `valgrind`)")?;
        if !run.status.success() {
            bail!("callgrind failed: {}", String::from_utf8_lossy(&run.stderr));
        }
        let stdout = String::from_utf8_lossy(&run.stdout);
        tets = stdout
            .lines()
            .find_map(|l| l.strip_prefix("tets"))
            .and_then(|v| v.trim().parse::<u64>().ok())
            .context("step_profile printed no tet count")?;
        counts.push(inclusive_counts(&out)?);
    }
    let tet_steps = (tets * (STEPS[1] - STEPS[0])) as f64;
    println!("instructions per tet-step ({tets} tets, steps {} to {}, 1 thread):", STEPS[0], STEPS[1]);
    for (k, (label, _)) in KERNELS.iter().enumerate() {
        println!("  {label:<8} {:>8.1}", (counts[1][k] - counts[0][k]) as f64 / tet_steps);
    }
    println!("  {:<8} {:>8.1}", "step", (counts[1][KERNELS.len()] - counts[0][KERNELS.len()]) as f64 / tet_steps);
    Ok(())
}

/// The inclusive count of each kernel, then the program total.
fn inclusive_counts(out: &Path) -> Result<Vec<u64>> {
    let annotate = Command::new("callgrind_annotate")
        .args(["--inclusive=yes", "--threshold=100"])
        .arg(out)
        .output()
        .context("running callgrind_annotate")?;
    let text = String::from_utf8_lossy(&annotate.stdout);
    let count = |line: &str| line.split_whitespace().next().and_then(|n| n.replace(',', "").parse::<u64>().ok());
    let mut counts = Vec::new();
    for (label, name) in KERNELS {
        // The function's own line ends with the object in brackets; the
        // lines without it break its cost down by source file.
        let line = text
            .lines()
            .find(|l| l.contains(&format!(":{name} [")))
            .with_context(|| format!("no `{name}` ({label}) in the profile"))?;
        counts.push(count(line).context("unreadable count")?);
    }
    let total = text.lines().find(|l| l.contains("PROGRAM TOTALS")).and_then(count).context("no program total")?;
    counts.push(total);
    Ok(counts)
}
