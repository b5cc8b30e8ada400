//! `femdem run --device gpu`: the bundled cases without contact, the
//! README's disc glued to its platens, and the README's run itself
//! (contact on the CPU beside the device) against the CPU, the refusals,
//! and determinism.
//!
//! Where the machine has no Vulkan device with 64-bit floats the device
//! tests say so and pass, unless `FEMDEM_GPU_REQUIRED` is set (`.ci/run`
//! sets it and installs lavapipe, Mesa's Vulkan on the CPU).
//!
//! # The tolerances
//!
//! Stage 1 on the device agrees with the CPU's to round-off per element
//! (`femdem-gpu`'s tests: 256 ε of each quantity's terms); the histories
//! of a whole run then differ by that round-off carried through the steps.
//! Until the first failure every column is compared against `10⁻⁹` of its
//! group's scale (displacements against the largest drive displacement,
//! forces and Eq. 21's load against the largest drive force or load, the
//! strain against the largest strain, work and energies against the
//! largest external work), which leaves a factor of about 10⁴ over the
//! per-step round-off of a few thousand steps. The stored elastic energy
//! and the balance are differences of terms of size `(λ + 2μ) V` (the
//! `‖F‖² − 3` of the neo-Hookean energy cancels), so their round-off does
//! not scale with the energy: the row of step 0, where every tet is
//! unstrained and the energy is round-off alone, shows its size, and the
//! tolerance adds 8 times it. After the first failure a run's course is
//! chaotic in its last bits (a joint failing a step earlier or later moves
//! what follows), so there the checks apply: the same failures,
//! the same peak load and energy balance.

use std::path::{Path, PathBuf};

use crate::common::{Table, col, failures, femdem, history};

/// Runs `case` with `--device device` into a fresh directory; `None` when
/// the device cannot be opened and `FEMDEM_GPU_REQUIRED` is not set.
fn run(case: &str, device: &str, name: &str, extra: &[&str]) -> Option<PathBuf> {
    let dir = std::env::temp_dir().join(format!("femdem-device-{name}-{device}"));
    let _ = std::fs::remove_dir_all(&dir);
    let mut args = vec!["run", case, "--out", dir.to_str().unwrap(), "--device", device];
    args.extend(extra);
    let o = femdem(&args);
    let stderr = String::from_utf8_lossy(&o.stderr);
    if !o.status.success()
        && stderr.contains("no device for the run")
        && std::env::var_os("FEMDEM_GPU_REQUIRED").is_none()
    {
        eprintln!("no device, GPU run not compared: {stderr}");
        return None;
    }
    assert!(o.status.success(), "{case} on {device}: {stderr}");
    // Mesa's software Vulkan (CI's device) runs correctly but slowly: said.
    if device == "gpu" && stderr.contains("on llvmpipe") {
        assert!(stderr.contains("is llvmpipe") && stderr.contains("a software device on the CPU"), "{stderr}");
    }
    Some(dir)
}

/// The largest `|value|` of the columns of `table` whose names satisfy
/// `pick`, over rows `rows`.
fn group_max(table: &Table, rows: usize, pick: impl Fn(&str) -> bool) -> f64 {
    let mut m: f64 = 0.0;
    for (k, name) in table.columns.iter().enumerate() {
        if pick(name) {
            for r in &table.rows[..rows] {
                m = m.max(r[k].abs());
            }
        }
    }
    m
}

/// Every column of the first `rows` rows of `a` and `b` within the module's
/// tolerance; returns the worst difference over its tolerance.
fn agree(a: &Table, b: &Table, rows: usize) -> f64 {
    assert_eq!(a.columns, b.columns);
    let is_u = |n: &str| n.ends_with("_ux") || n.ends_with("_uy") || n.ends_with("_uz");
    // The load-strain columns (Eq. 21) are a force and a displacement over
    // a length: compared with the forces and with their own scale.
    let is_f = |n: &str| n.ends_with("_fx") || n.ends_with("_fy") || n.ends_with("_fz") || n == "load";
    let strain = group_max(a, rows, |n| n == "strain");
    let u = group_max(a, rows, is_u);
    let f = group_max(a, rows, is_f);
    let w = group_max(a, rows, |n| n == "external_work" || n == "kinetic");
    let stored = |n: &str| n == "tet_elastic" || n == "joint_elastic" || n == "balance";
    let mut worst: f64 = 0.0;
    for (k, name) in a.columns.iter().enumerate() {
        let tol = if is_u(name) {
            1e-9 * u
        } else if is_f(name) {
            1e-9 * f
        } else if name == "strain" {
            1e-9 * strain
        } else if stored(name) {
            1e-9 * w + 8.0 * a.rows[0][k].abs().max(b.rows[0][k].abs())
        } else if name == "time" || name == "step" || name.starts_with("broken_") {
            0.0
        } else {
            1e-9 * w
        };
        for (ra, rb) in a.rows[..rows].iter().zip(&b.rows[..rows]) {
            let d = (ra[k] - rb[k]).abs();
            assert!(d <= tol, "column {name} at t = {:e}: {} vs {} (tolerance {tol:e})", ra[0], ra[k], rb[k]);
            if tol > 0.0 {
                worst = worst.max(d / tol);
            }
        }
    }
    worst
}

/// The elastic bar (no joints): every row agrees.
#[test]
fn the_elastic_bar_on_the_device_agrees_with_the_cpu() {
    let Some(gpu) = run("cases/elastic-bar.toml", "gpu", "bar", &[]) else { return };
    let cpu = run("cases/elastic-bar.toml", "cpu", "bar", &[]).unwrap();
    let (a, b) = (history(&cpu), history(&gpu));
    assert_eq!(a.rows.len(), b.rows.len());
    let worst = agree(&a, &b, a.rows.len());
    println!("elastic bar: worst difference {worst:.2e} of its tolerance");
}

/// `case` on the device and on the CPU, a run whose joints fail: the rows
/// before the first failure agree to round-off; then the same joints fail
/// at the same steps in the same modes, and the peak of column `load`, the
/// failure counts and the balance agree. `extra` are more arguments.
fn fails_as_on_the_cpu(case: &str, name: &str, load: &str, extra: &[&str]) {
    let Some(gpu) = run(case, "gpu", name, extra) else { return };
    let cpu = run(case, "cpu", name, extra).unwrap();
    let (a, b) = (history(&cpu), history(&gpu));
    assert_eq!(a.rows.len(), b.rows.len());
    let list = |dir: &Path| {
        let all = femdem_post::failures::Failure::read_all(dir).unwrap();
        all.iter().map(|f| (f.time, f.joint, f.mode)).collect::<Vec<_>>()
    };
    let first = list(&cpu).iter().map(|f| f.0).fold(f64::MAX, f64::min);
    let before = a.rows.iter().take_while(|r| r[0] < first).count();
    assert!(before > 10, "{name}: rows before the first failure: {before}");
    let worst = agree(&a, &b, before);
    assert!(failures(&cpu) > 10, "{name}: the run breaks joints");
    assert_eq!(list(&cpu), list(&gpu), "{name}: the same failures at the same steps in the same modes");
    let last = a.rows.len() - 1;
    for column in ["broken_tensile", "broken_shear", "broken_mixed", "broken_collapsed"] {
        assert_eq!(a.rows[last][col(&a, column)], b.rows[last][col(&b, column)], "{name}: {column}");
    }
    let f = col(&a, load);
    let peak = |t: &Table| t.rows.iter().map(|r| r[f].abs()).fold(0.0, f64::max);
    let (pa, pb) = (peak(&a), peak(&b));
    let work = a.rows[last][col(&a, "external_work")];
    let (ba, bb) = (a.rows[last][col(&a, "balance")], b.rows[last][col(&b, "balance")]);
    println!(
        "{name}: {before} rows before the first failure, worst {worst:.2e} of the tolerance; peak {pa} N vs {pb} N; balance {ba:e} vs {bb:e} J of {work:e} J"
    );
    assert!((pa - pb).abs() <= 1e-6 * pa, "{name}: peak {pa} vs {pb}");
    assert!((ba - bb).abs() <= 1e-6 * work, "{name}: balance {ba} vs {bb}");
}

/// The pulled bar (joints that fail).
#[test]
fn the_pulled_bar_on_the_device_fails_as_on_the_cpu() {
    fails_as_on_the_cpu("cases/pulled-bar.toml", "pulled", "pull_fz", &[]);
}

/// The README's Brazilian disc glued to its platens (each platen drives
/// the disc's nodes on its side of the loaded diameter, `|x| ≤ 0.1 mm`,
/// `|y| ≥ 19.9 mm`; no contact), to its split: joints, rigid platens,
/// viscous damping and the load–strain stop, written from
/// `cases/brazilian-split.toml` by removing `[contact]` and adding the
/// platens' `drives`.
#[test]
fn the_glued_disc_on_the_device_splits_as_on_the_cpu() {
    let text = std::fs::read_to_string(crate::common::root().join("cases/brazilian-split.toml")).unwrap();
    let (from, to) = (text.find("[contact]").unwrap(), text.find("[solver]").unwrap());
    let mut glued = format!("{}{}", &text[..from], &text[to..]);
    for (side, ys) in [("top", "0.0199, -1.0], max = [1e-4, 1.0"), ("bottom", "-1.0, -1.0], max = [1e-4, -0.0199")] {
        let platen = format!("[[platens]]\nregion = \"platen_{side}\"\n");
        assert!(glued.contains(&platen), "the README case's {side} platen");
        let drives = format!("{platen}drives = {{ group = \"disc.side\", box = {{ min = [-1e-4, {ys}, 1.0] }} }}\n");
        glued = glued.replace(&platen, &drives);
    }
    let case = std::env::temp_dir().join("femdem-device-glued.toml");
    std::fs::write(&case, glued).unwrap();
    fails_as_on_the_cpu(case.to_str().unwrap(), "glued", "load", &[]);
}

/// Two device runs of the same case write the same bytes.
#[test]
fn two_device_runs_write_the_same_bytes() {
    let Some(one) = run("cases/pulled-bar.toml", "gpu", "twice-1", &["--set", "solver.end_time=1.8e-4"]) else {
        return;
    };
    let two = run("cases/pulled-bar.toml", "gpu", "twice-2", &["--set", "solver.end_time=1.8e-4"]).unwrap();
    assert!(failures(&one) > 0, "the window includes failures");
    for file in ["history.csv", "failures.csv"] {
        assert_eq!(read(&one, file), read(&two, file), "{file}");
    }
}

/// A device run stopped after its first failures and resumed on the
/// device ends as the uninterrupted one (the checkpoint brings the joint
/// histories back from the device, the resume sends them there again).
#[test]
fn a_device_run_resumes_bit_for_bit() {
    let args = ["--set", "solver.end_time=1.8e-4", "--set", "output.checkpoint.interval_steps=0"];
    let Some(whole) = run("cases/pulled-bar.toml", "gpu", "whole", &args) else { return };
    let dir = std::env::temp_dir().join("femdem-device-resumed");
    let _ = std::fs::remove_dir_all(&dir);
    let out = dir.to_str().unwrap();
    let mut first = vec!["run", "cases/pulled-bar.toml", "--out", out, "--device", "gpu", "--stop-after-steps", "2350"];
    first.extend(args);
    let o = femdem(&first);
    assert!(!o.status.success(), "a stopped run ends with an error status");
    assert!(failures(&dir) > 0, "stopped after failures");
    let mut again = vec!["run", "cases/pulled-bar.toml", "--device", "gpu", "--resume", out];
    again.extend(args);
    let o = femdem(&again);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for file in ["history.csv", "failures.csv"] {
        assert_eq!(without_comments(&read(&whole, file)), without_comments(&read(&dir, file)), "{file}");
    }
}

/// The README's run (platens in contact from the first step, a crack
/// whose faces touch) with the bulk on the device and contact on the CPU,
/// through its peak (4.09e-4 s) and its first failures (22 when written;
/// the comparison asks for more than 10): every row
/// before the first failure within the module's tolerance, then the same
/// failures, peak and balance as on the CPU; the summary names the stages.
#[test]
fn the_readme_run_on_the_device_splits_as_on_the_cpu() {
    let args = ["--set", "solver.end_time=4.4e-4"];
    fails_as_on_the_cpu("cases/brazilian-split.toml", "readme", "load", &args);
    if let Some(dir) = run("cases/brazilian-split.toml", "gpu", "readme-header", &["--set", "solver.end_time=1e-6"]) {
        let header = read(&dir, "history.csv");
        assert!(header.contains("the contact pairs' Eq. 17; failures, the rest of contact, drives"), "{header}");
    }
}

/// An unknown device is refused naming the key.
#[test]
fn unknown_devices_are_refused() {
    let dir = std::env::temp_dir().join("femdem-device-refused");
    let out = dir.to_str().unwrap();
    let o = femdem(&["run", "cases/pulled-bar.toml", "--out", out, "--overwrite", "--device", "tpu"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && stderr.contains("--device: `device`: `tpu` is not one of cpu, gpu"), "{stderr}");
    let o = femdem(&["run", "cases/pulled-bar.toml", "--out", out, "--overwrite", "--set", "solver.device=\"fpga\""]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && stderr.contains("pulled-bar.toml") && stderr.contains("`fpga` is not one of"),
        "{stderr}"
    );
}

fn read(dir: &Path, file: &str) -> String {
    std::fs::read_to_string(dir.join(file)).unwrap_or_else(|e| panic!("{}: {e}", dir.join(file).display()))
}

fn without_comments(text: &str) -> String {
    text.lines().filter(|l| !l.starts_with('#')).collect::<Vec<_>>().join("\n")
}
