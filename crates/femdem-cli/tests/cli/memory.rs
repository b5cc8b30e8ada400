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

/// Two traces 2 mm apart in an outline meshed at 0.1 m: the extrusion
/// refines to the gap (5,250 tets where `element_size` gives 416), which
/// the estimate from the parts' sizes cannot see. `check` warns with the
/// part, the ratio and the shortest edge's place (on the gap, between
/// the traces' lines y = 0.2 + x/3 and 2 mm above); with memory enough
/// for the sizes' estimate (about 0.9 MB) but not for the mesh built
/// (about 11 MB), `check` and `run` refuse it once built, with the
/// warning, and `--force` lets it through.
#[test]
fn a_mesh_refined_beyond_its_sizes_is_named_and_checked_again_once_built() {
    let case = root().join("tests/cases/crowded_traces.toml");
    let case = case.to_str().unwrap();
    let o = femdem(&["check", case]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    let warning = stderr.lines().find(|l| l.starts_with("warning:")).expect("a warning");
    assert!(warning.contains("crowded_traces.toml:11:1: mesh.parts[0]: 5250 tets, 13 times the 416"), "{warning}");
    let coordinate = |name: &str| -> f64 {
        let from = warning.find(&format!("{name} = ")).unwrap() + name.len() + 3;
        warning[from..].split([',', ' ']).next().unwrap().parse().unwrap()
    };
    let (x, y) = (coordinate("x"), coordinate("y"));
    let below = 0.2 + (x - 0.2) / 3.0;
    assert!((0.2..=0.8).contains(&x) && y > below - 1e-3 && y < below + 3e-3, "({x}, {y}) is not on the gap");

    let out = std::env::temp_dir().join("femdem-crowded-traces");
    let _ = std::fs::remove_dir_all(&out);
    for command in ["check", "run"] {
        let mut args = vec![command, case, "--memory-available", "5e6"];
        if command == "run" {
            args.extend(["--out", out.to_str().unwrap()]);
        }
        let o = femdem(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{command}: {stderr}");
        assert!(stderr.contains("crowded_traces.toml: the mesh built has 5.250e3 tets"), "{stderr}");
        assert!(stderr.contains("(--memory-available); use a larger element_size, or --force"), "{stderr}");
        assert!(stderr.contains("warning: ") && stderr.contains("13 times the 416"), "{stderr}");
        args.push("--force");
        let o = femdem(&args);
        assert!(o.status.success(), "{command} --force: {}", String::from_utf8_lossy(&o.stderr));
    }
    let _ = std::fs::remove_dir_all(&out);
}

/// An MSH part is estimated where its `scale` and `translate` put it: a
/// platen after it takes its default extent from the placed mesh (the
/// fixture's 10 mm cube scaled to 10 m), so the estimate is the one with
/// that extent given, 10 m × 10 m; from the file's own coordinates it
/// would be a platen of 10 mm (six tets instead of 600).
#[test]
fn an_msh_part_is_estimated_where_it_is_placed() {
    let case = root().join("tests/cases/scaled_msh_with_platen.toml");
    let case = case.to_str().unwrap();
    let report = |sets: &[&str]| {
        let mut args = vec!["check", case, "--json"];
        for s in sets {
            args.extend(["--set", s]);
        }
        let out = femdem(&args);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        serde_json::from_slice::<serde_json::Value>(&out.stdout).unwrap()
    };
    let default = report(&[]);
    let given = report(&["mesh.parts.1.extent=[10.0, 10.0]"]);
    assert_eq!(default["tets"], given["tets"]);
    assert_eq!(default["tets"], 403 + 600);
    assert_eq!(default["estimated_memory_bytes"], given["estimated_memory_bytes"]);
}
