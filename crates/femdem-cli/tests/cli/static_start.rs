//! `[solver] start = "static"` end to end: the run reports its static
//! solve, starts at rest under the held pressures (the ramp is ignored),
//! and its energy account starts balanced; it is the same bit for bit on
//! one thread or two, and when stopped and resumed (the resumed run does
//! not solve again); the default start is unchanged.

use crate::common::{femdem, history_csv, root};
use std::path::Path;

/// The history's column names and rows (`femdem_post`).
fn history(dir: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let t = crate::common::history(dir);
    (t.columns, t.rows)
}

/// The cube's surface loads are held from the first row, the body is at
/// rest under them (its kinetic energy below 10⁻⁸ of the stored energy: a
/// vibration amplitude below 10⁻⁴ of the static displacement, as in
/// femdem-static's `at_rest` test), and the stored energy is booked as the
/// loads' work (the balance starts at zero).
#[test]
fn a_static_start_runs_at_rest_under_the_held_loads() {
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("static-start-run");
    let _ = std::fs::remove_dir_all(&out);
    let o = femdem(&["run", "crates/femdem-cli/tests/cases/static_start.toml", "--out", out.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(stderr.contains("static start:") && stderr.contains("1 free"), "{stderr}");
    let (header, rows) = history(&out);
    let col = |name: &str| header.iter().position(|c| c == name).unwrap();
    let first = &rows[0];
    let load = first[col("cube.ymax_fy")];
    // The full pressure from the first row: 1.5 MPa on 0.04 × 0.04 m².
    assert!((load / -2400.0 - 1.0).abs() < 1e-3, "ymax load {load} N at t = 0");
    for r in &rows {
        let stored = r[col("tet_elastic")] + r[col("joint_elastic")];
        assert!(
            stored > 0.0 && r[col("kinetic")] < 1e-8 * stored,
            "t = {}: kinetic {}",
            r[col("time")],
            r[col("kinetic")]
        );
        assert!(r[col("balance")].abs() < 1e-6 * stored, "t = {}: balance {}", r[col("time")], r[col("balance")]);
    }
}

/// `start = "dynamic"` is the default: the run is the same bit for bit.
#[test]
fn the_dynamic_start_is_the_default() {
    let case = root().join("crates/femdem-cli/tests/cases/static_start.toml");
    let text = std::fs::read_to_string(&case).unwrap();
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("dynamic-start");
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp).unwrap();
    let mut histories = Vec::new();
    for (name, start) in [("default", ""), ("named", "start = \"dynamic\"")] {
        let file = tmp.join(format!("{name}.toml"));
        std::fs::write(&file, text.replace("start = \"static\"", start)).unwrap();
        let out = tmp.join(name);
        let o = femdem(&["run", file.to_str().unwrap(), "--out", out.to_str().unwrap()]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(!String::from_utf8_lossy(&o.stderr).contains("static start"));
        // The header and rows: the comment lines name each case file.
        histories.push(history_csv(&out));
    }
    assert_eq!(histories[0], histories[1]);
}

/// The history of the static case run with `extra` arguments into `name`.
fn run_static(name: &str, extra: &[&str]) -> (String, String) {
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&out);
    let mut args = vec!["run", "crates/femdem-cli/tests/cases/static_start.toml", "--out", out.to_str().unwrap()];
    args.extend_from_slice(extra);
    let o = femdem(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    (std::fs::read_to_string(out.join("history.csv")).unwrap(), String::from_utf8_lossy(&o.stderr).into_owned())
}

#[test]
fn a_static_start_does_not_depend_on_the_thread_count() {
    let (one, _) = run_static("static-start-1-thread", &["--threads", "1"]);
    let (two, _) = run_static("static-start-2-threads", &["--threads", "2"]);
    // The header names the threads (provenance); every row is the same.
    let rows = |h: &str| h.lines().filter(|l| !l.starts_with('#')).map(str::to_owned).collect::<Vec<_>>();
    assert_eq!(rows(&one), rows(&two));
    assert!(one.contains("\n# threads: 1\n") && two.contains("\n# threads: 2\n"));
}

#[test]
fn a_static_start_stopped_and_resumed_is_identical() {
    let (whole, _) = run_static("static-start-whole", &[]);
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("static-start-stopped");
    let _ = std::fs::remove_dir_all(&out);
    let case = "crates/femdem-cli/tests/cases/static_start.toml";
    let o = femdem(&["run", case, "--out", out.to_str().unwrap(), "--stop-after-steps", "30"]);
    assert!(!o.status.success(), "a stopped run exits non-zero");
    let o = femdem(&["run", case, "--resume", out.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(!stderr.contains("static start:"), "the resumed run solved again: {stderr}");
    assert_eq!(std::fs::read_to_string(out.join("history.csv")).unwrap(), whole);
}
