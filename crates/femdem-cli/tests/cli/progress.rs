//! The progress lines of `femdem run` (plain lines, as on a log file or a
//! pipe) carry the number of failed joints and, with
//! `[output.load_strain]`, the load: on the small Brazilian disc, whose
//! joints start failing at step ~760, they count up to the number of rows
//! of `failures.csv`, and the last line's load is the last history row's.

use crate::common::{col, failures, history, root};
use std::path::Path;
use std::process::Command;

#[test]
fn progress_lines_carry_the_failed_joints_and_the_load() {
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("progress-lines");
    let _ = std::fs::remove_dir_all(&out);
    let o = Command::new(env!("CARGO_BIN_EXE_femdem"))
        .args(["run", "crates/femdem-cli/tests/cases/small_brazilian.toml", "--out", out.to_str().unwrap()])
        .args(["--progress-interval", "0"])
        .current_dir(root())
        .output()
        .expect("run femdem");
    let stderr = String::from_utf8(o.stderr).unwrap();
    assert!(o.status.success(), "{stderr}");
    // `step N/M  t = T s  K joints failed  load F N  R element-steps/s  eta E s`
    let lines: Vec<(usize, f64)> = stderr
        .lines()
        .filter(|l| l.starts_with("step "))
        .map(|l| {
            let failed =
                l.split("  ").find_map(|f| f.strip_suffix(" joints failed").or(f.strip_suffix(" joint failed")));
            let load = l.split("  ").find_map(|f| f.strip_prefix("load ")?.strip_suffix(" N"));
            (failed.unwrap_or_else(|| panic!("no failures: {l}")).parse().unwrap(), load.unwrap().parse().unwrap())
        })
        .collect();
    assert!(lines.len() > 1000, "a line per step: {}", lines.len());
    assert!(lines.windows(2).all(|w| w[0].0 <= w[1].0), "the failure count never falls");
    let failures = failures(&out);
    let (failed, load) = *lines.last().unwrap();
    assert!(failures > 0);
    assert_eq!(failed, failures, "the last line counts every failure");
    let history = history(&out);
    let last = history.rows.last().unwrap()[col(&history, "load")];
    // The line prints 5 significant digits.
    assert!((load - last).abs() <= 1e-4 * last.abs(), "load {load} on the line, {last} in the history");
    let peak = lines.iter().map(|l| l.1).fold(0.0, f64::max);
    assert!(peak > 2.0 * last, "the lines show the load rise and fall past the peak: peak {peak}, last {last}");
}
