//! The memory estimate: `femdem run` refuses a case whose mesh would not
//! fit in the available memory, from the parts' sizes, before meshing.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

fn femdem(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_femdem")).args(args).current_dir(root()).output().expect("run femdem")
}

/// `MemAvailable` in bytes (Linux).
fn available() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let kib: f64 = text.lines().find(|l| l.starts_with("MemAvailable:"))?.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024.0)
}

/// 1.8e8 tets (under the 2e8 cap) need about 3.5e11 bytes: refused in well
/// under a second, where meshing it would take minutes and then fail.
#[test]
fn a_run_that_cannot_fit_in_memory_is_refused_before_meshing() {
    let Some(available) = available() else {
        eprintln!("no /proc/meminfo: the refusal is Linux-only; skipped");
        return;
    };
    if available > 3.5e11 {
        eprintln!("{available:.3e} bytes available: the case would fit; skipped");
        return;
    }
    let case = root().join("tests/cases/too_big_for_memory.toml");
    let start = Instant::now();
    let out = femdem(&[
        "run",
        case.to_str().unwrap(),
        "--out",
        std::env::temp_dir().join("femdem-too-big").to_str().unwrap(),
    ]);
    let elapsed = start.elapsed().as_secs_f64();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(stderr.contains("too_big_for_memory.toml: the mesh would need about"), "{stderr}");
    assert!(
        stderr.contains("1.800e8 tets") && stderr.contains("MemAvailable") && stderr.contains("--force"),
        "{stderr}"
    );
    assert!(elapsed < 5.0, "refused after {elapsed} s: it must not mesh first");
}

/// `femdem check` reports the estimate next to the arrays it built.
#[test]
fn check_reports_the_estimate() {
    let out = femdem(&["check", root().join("tests/cases/bad/crushed_cube.toml").to_str().unwrap(), "--json"]);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let estimate = report["estimated_memory_bytes"].as_f64().expect("an estimate");
    let arrays = report["memory_bytes"].as_f64().unwrap();
    assert!(estimate > arrays, "estimate {estimate} vs the jointed mesh's arrays {arrays}");
}
