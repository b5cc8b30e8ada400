//! `--set key.path=value` on `femdem check` and `femdem run`: overridden
//! values are used, refused ones are refused with the message the same
//! value in the file gets but naming the `--set` argument instead of a
//! line, and `--resume` needs the overrides of the run it continues.

use std::path::{Path, PathBuf};

use crate::common::{femdem, root};
use serde_json::Value;

const CASE: &str = "crates/femdem-cli/tests/cases/small_brazilian.toml";

fn fresh(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn check_json(args: &[&str]) -> Value {
    let out = femdem(&[&["check", "--json"], args].concat());
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("one JSON object")
}

/// `femdem check` with `args` fails; its error message.
fn refused(args: &[&str]) -> String {
    let out = femdem(&[&["check"], args].concat());
    assert!(!out.status.success(), "{args:?} must be refused");
    String::from_utf8(out.stderr).unwrap()
}

/// Whether `err` has a `file.toml:LINE:` location.
fn has_line(err: &str) -> bool {
    err.match_indices(".toml:").any(|(i, m)| err[i + m.len()..].starts_with(|c: char| c.is_ascii_digit()))
}

/// The case `CASE` with `from` replaced by `to`, written under `dir` with
/// the same file name (its relative paths stay valid: it has none).
fn edited(dir: &Path, from: &str, to: &str) -> PathBuf {
    let text = std::fs::read_to_string(root().join(CASE)).unwrap();
    assert!(text.contains(from), "`{from}` is not in the case");
    let path = dir.join("small_brazilian.toml");
    std::fs::write(&path, text.replacen(from, to, 1)).unwrap();
    path
}

#[test]
fn overridden_values_are_used_and_listed() {
    let base = check_json(&[CASE]);
    let set = check_json(&[
        CASE,
        "--set",
        "solver.end_time=1e-4",
        "--set",
        "mesh.parts.0.element_size=2e-3",
        "--set",
        "title = \"finer\"",
    ]);
    assert_eq!(
        set["overrides"],
        serde_json::json!(["solver.end_time=1e-4", "mesh.parts.0.element_size=2e-3", "title = \"finer\""])
    );
    assert_eq!(set["title"], "finer");
    assert!(set["tets"].as_u64() > base["tets"].as_u64(), "a finer disc has more tets");
    // Half the end time at the step of the finer mesh.
    let t = &set["time_stepping"];
    let steps = (1e-4 / t["time_step"].as_f64().unwrap()).ceil();
    assert_eq!(t["steps"].as_f64().unwrap(), steps);
    assert_eq!(base["overrides"], serde_json::json!([]));
    // Keys the file does not have are added, with their tables.
    let added = check_json(&[
        CASE,
        "--set",
        "contact.buffer=1e-4",
        "--set",
        "output.checkpoint.interval_steps=100",
        "--set",
        "heterogeneity = { distribution = \"weibull\", modulus = 8.0 }",
    ]);
    assert_eq!(added["tets"], base["tets"]);
}

#[test]
fn refused_overrides_name_the_argument_not_a_line() {
    for (set, words) in [
        ("solver.end_time=-1", "solver: end_time must be > 0 s, got -1"),
        ("solver.end_tim=1", "unknown field `end_tim`, expected one of `end_time`"),
        ("mesh.parts.0.elemnt_size=1", "unknown field `elemnt_size`"),
        ("materials.0.tensile_strength=\"2e6\"", "invalid type: string \"2e6\", expected f64"),
        ("materials.0.tensile_strength=-2e6", "materials[0]: invalid joint parameter `tensile_strength`"),
        ("output.interval=0", "output: `interval` must be finite and > 0 s"),
        ("output.compression=\"bzip\"", "`compression`: `bzip` is not one of"),
        ("heterogeneity.modulus=8", "missing field `distribution`"),
        ("materials.3.young=1", "`materials` has 1 entry: there is no entry 3"),
        ("materials.x.young=1", "`materials` is an array: `x` is not the index of an entry (its one entry is 0)"),
        ("platens.x.velocity=[0.0, 0.0, 0.0]", "`platens` is an array: `x` is not the index of an entry (0 to 1)"),
        ("solver.gravity.2=-9.81", "`solver.gravity` is not in the case"),
        ("solver.end_time.x=1", "`solver.end_time` is a number, not a table"),
        ("output.dir=out/x", "`out/x` is not a TOML value"),
        ("solver.end_time", "expected KEY=VALUE"),
        ("solver end_time=1", "is not a key path"),
    ] {
        let err = refused(&[CASE, "--set", set]);
        assert!(err.contains(&format!("small_brazilian.toml: --set {set}: ")), "{set}: {err}");
        assert!(err.contains(words), "{set}: {err}");
        assert!(!has_line(&err), "{set}: an override's error has no line of the file: {err}");
    }
    let err = refused(&[CASE, "--set", "solver.end_time=1", "--set", "solver.end_time=2"]);
    assert!(err.contains("already set by --set solver.end_time=1"), "{err}");
}

/// An override gets the message the same value gets in the file; only the
/// place differs (the argument instead of `file:line:col` and, for a value
/// of the wrong type, its key).
#[test]
fn an_override_is_refused_as_the_same_value_in_the_file() {
    let dir = fresh("set-as-in-file");
    for (from, to, set) in [
        ("end_time = 2.0e-4", "end_time = -1.0", "solver.end_time=-1.0"),
        ("end_time = 2.0e-4", "end_time = 2.0e-4\nend_tim = 1", "solver.end_tim=1"),
        ("tensile_strength = 3.0e6", "tensile_strength = \"3e6\"", "materials.0.tensile_strength=\"3e6\""),
        ("interval = 2.0e-5", "interval = 0.0", "output.interval=0.0"),
    ] {
        let file = edited(&dir, from, to);
        let in_file = refused(&[file.to_str().unwrap()]);
        let by_set = refused(&[CASE, "--set", set]);
        // `error: FILE:LINE:COL: MESSAGE` and `error: FILE: --set ARG: MESSAGE`.
        assert!(has_line(&in_file), "{in_file}");
        let after_line = in_file.split_once(".toml:").unwrap().1.splitn(3, ':').nth(2).unwrap();
        let after_set = by_set.split_once(&format!("--set {set}: ")).unwrap().1;
        // The file's message of a bad value names its key, as the argument does.
        let key = set.split('=').next().unwrap().rsplit('.').next().unwrap();
        let after_line = after_line.trim();
        let after_line = after_line.strip_prefix(&format!("`{key}`: ")).unwrap_or(after_line);
        assert_eq!(after_set.trim(), after_line, "{set}");
    }
}

/// An error of the file in a table an override also sets a key of keeps
/// its line when the message names another key, and names the override
/// in a note.
#[test]
fn a_file_error_beside_an_override_keeps_its_line() {
    let dir = fresh("set-beside-file-error");
    let file = edited(&dir, "end_time = 2.0e-4", "end_time = -1.0");
    let err = refused(&[file.to_str().unwrap(), "--set", "solver.safety=0.5"]);
    assert!(has_line(&err) && !err.contains(".toml: --set"), "{err}");
    assert!(
        err.contains("solver: end_time must be > 0 s, got -1 (this table also has --set solver.safety=0.5)"),
        "{err}"
    );
}

/// The history of a run in `out` with the extra arguments `args`.
fn run(out: &Path, args: &[&str]) -> std::process::Output {
    femdem(&[&["run", CASE, "--out", out.to_str().unwrap()], args].concat())
}

/// A run with overrides, stopped and resumed: a resume without them, or
/// with others, is refused naming both sets; with the same ones (in
/// another order and spelling) it ends as the uninterrupted run with them.
#[test]
fn a_resume_needs_the_overrides_of_the_run_it_continues() {
    let sets = ["--set", "solver.end_time=5e-5", "--set", "output.history_interval=2e-6"];
    let base = fresh("set-resume-base");
    let o = run(&base, &sets);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stderr).contains("femdem: with --set solver.end_time=5e-5"));

    let out = fresh("set-resume-stopped");
    let o = run(&out, &[&sets[..], &["--stop-after-steps", "300"]].concat());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(
        err.contains("--resume") && err.contains("--set 'solver.end_time=5e-5'"),
        "the hint repeats the overrides: {err}"
    );

    let dir = out.to_str().unwrap();
    for other in [&[][..], &["--set", "solver.end_time=5e-5"][..]] {
        let o = femdem(&[&["run", CASE, "--resume", dir], other].concat());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{other:?}: a resume with other overrides is refused");
        assert!(err.contains("--set overrides differ"), "{err}");
        assert!(
            err.contains("the checkpoint's: --set output.history_interval=0.000002 --set solver.end_time=0.00005"),
            "{err}"
        );
    }
    let same = ["--set", "output.history_interval = 0.000002", "--set", "solver.end_time=0.00005"];
    let o = femdem(&[&["run", CASE, "--resume", dir], &same[..]].concat());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for file in ["history.csv", "failures.csv", "small_brazilian.pvd"] {
        let (a, b) = (std::fs::read(base.join(file)).unwrap(), std::fs::read(out.join(file)).unwrap());
        assert!(a == b, "{file} differs from the uninterrupted run's");
    }
    // The overrides were those of the resumed run: it ended at 50 µs.
    let history = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let last: f64 = history.lines().last().unwrap().split(',').next().unwrap().parse().unwrap();
    assert!((4.9e-5..5.0e-5).contains(&last), "last row at t = {last} s");
}
