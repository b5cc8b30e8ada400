//! The memory estimate: `femdem run` refuses a case whose mesh would not
//! fit in the available memory, from the parts' sizes, before meshing.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

fn femdem(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_femdem")).args(args).current_dir(root()).output().expect("run femdem")
}

/// 1.8e8 tets (under the 2e8 cap) need about 3.5e11 bytes. With 16 GiB
/// available (`--memory-available`, so the test does not depend on the
/// machine) both `run` and `check` refuse it from the parts' sizes, before
/// meshing: `run` has not created its output directory (it would before
/// the mesh), and the message names the figures and `--force`.
#[test]
fn a_case_that_cannot_fit_in_memory_is_refused_before_meshing() {
    let case = root().join("tests/cases/too_big_for_memory.toml");
    let case = case.to_str().unwrap();
    let out = std::env::temp_dir().join("femdem-too-big");
    let _ = std::fs::remove_dir_all(&out);
    let gib16 = (16u64 << 30).to_string();
    for command in ["run", "check"] {
        let mut args = vec![command, case, "--memory-available", &gib16];
        if command == "run" {
            args.extend(["--out", out.to_str().unwrap()]);
        }
        let o = femdem(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{command}");
        assert!(stderr.contains("too_big_for_memory.toml: the mesh would need about"), "{stderr}");
        assert!(stderr.contains("1.800e8 tets") && stderr.contains("16.0 GiB"), "{stderr}");
        assert!(
            stderr.contains("(--memory-available)") && stderr.contains(&format!("{command} with --force")),
            "{stderr}"
        );
    }
    assert!(!out.exists(), "the run got as far as its output directory");
    let o = femdem(&["check", case, "--memory-available=-1"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && stderr.contains("--memory-available must be"), "{stderr}");
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
