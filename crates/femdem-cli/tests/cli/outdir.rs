//! Output hygiene: a run refuses a directory holding an earlier run's
//! results (naming the directory, the case they belong to and the way
//! out) and leaves it untouched; `--overwrite` removes femdem's own files
//! first — no stale frame survives, a user's file and folder do; dangerous
//! targets (`/`, the home directory, the case file's own folder, a file)
//! are refused whatever the flags; `history.csv` names its case in comment
//! lines before the header.

use crate::common::{femdem, root};
use std::path::{Path, PathBuf};
use std::process::Command;

const BAR: &str = "cases/elastic-bar.toml";

fn fresh(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// `femdem run CASE --out OUT ARGS…`.
fn run(case: &str, out: &Path, args: &[&str]) -> std::process::Output {
    femdem(&[&["run", case, "--out", out.to_str().unwrap()], args].concat())
}

/// The `.vtu` files in `dir` and the files its `.pvd`s list.
fn frames(dir: &Path) -> (Vec<String>, Vec<String>) {
    let mut on_disk = Vec::new();
    let mut listed = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        if name.ends_with(".vtu") {
            on_disk.push(name);
        } else if name.ends_with(".pvd") {
            let pvd = std::fs::read_to_string(dir.join(&name)).unwrap();
            listed.extend(pvd.split("file=\"").skip(1).map(|s| s.split('"').next().unwrap().to_owned()));
        }
    }
    on_disk.sort();
    listed.sort();
    (on_disk, listed)
}

/// The run's history starts with comment lines naming the case, its title
/// and the overrides, and what produced it (femdem's version and commit,
/// the processor, the build's vector instructions, the threads, the GPU),
/// then the header.
#[test]
fn the_history_names_its_case_before_the_header() {
    let out = fresh("outdir-comments");
    let o = run(BAR, &out, &["--set", "solver.end_time=1e-5"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let history = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let lines: Vec<&str> = history.lines().take(9).collect();
    assert_eq!(lines[0], "# case: elastic-bar.toml");
    assert_eq!(lines[1], "# title: P-wave in a confined bar");
    // The overrides in the form a checkpoint records them (TOML's spelling).
    assert_eq!(lines[2], "# set: solver.end_time=0.00001");
    assert!(lines[3].starts_with(&format!("# femdem: {} (commit ", env!("CARGO_PKG_VERSION"))), "{lines:?}");
    for (line, key) in lines[4..8].iter().zip(["cpu", "simd", "threads", "gpu"]) {
        assert!(line.starts_with(&format!("# {key}: ")), "{lines:?}");
    }
    assert!(lines[8].starts_with("time,step,kinetic"), "{lines:?}");
    // The run summary names them too.
    let summary = String::from_utf8_lossy(&o.stdout);
    assert!(summary.lines().any(|l| l.starts_with("built       femdem ") && l.contains("simd")), "{summary}");
}

/// A second run into the same directory is refused and writes nothing; with
/// `--overwrite` and fewer frames, the earlier frames, series and plots are
/// gone (every frame on disk is listed) and the user's file and folder stay.
#[test]
fn a_second_run_is_refused_until_overwrite_clears_the_first() {
    let out = fresh("outdir-overwrite");
    let o = run(BAR, &out, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = femdem(&["plot", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.join("plot_energies.png").is_file());
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    std::fs::create_dir_all(out.join("mine")).unwrap();
    let (before, _) = frames(&out);
    let history = std::fs::read(out.join("history.csv")).unwrap();

    let o = run(BAR, &out, &["--set", "output.interval=2e-5"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "a second run must be refused");
    assert!(
        err.contains(&format!(
            "output directory {} already holds the results of an earlier run of this case",
            out.display()
        )),
        "{err}"
    );
    assert!(err.contains("elastic-bar.pvd with 21 frames") && err.contains("history.csv"), "{err}");
    assert!(err.contains("--overwrite") && err.contains("notes.txt") && err.contains("--out"), "{err}");
    assert_eq!(std::fs::read(out.join("history.csv")).unwrap(), history, "the refused run wrote nothing");
    assert_eq!(frames(&out).0, before);

    let o = run(BAR, &out, &["--set", "output.interval=2e-5", "--overwrite"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("--overwrite: removed the results of an earlier run") && err.contains("kept 2 entries"),
        "{err}"
    );
    let (on_disk, listed) = frames(&out);
    assert_eq!(on_disk, listed, "no stale frame is left");
    assert!(on_disk.len() < before.len(), "{} frames, {} before", on_disk.len(), before.len());
    assert!(!out.join("plot_energies.png").exists(), "the earlier plots went with their results");
    assert_eq!(std::fs::read_to_string(out.join("notes.txt")).unwrap(), "mine");
    assert!(out.join("mine").is_dir());
}

/// The refusal names the case the results belong to, from the history's
/// comment line; `--overwrite` cannot be combined with `--resume`.
#[test]
fn another_cases_results_are_refused_naming_that_case() {
    let out = fresh("outdir-other-case");
    let o = run("cases/pulled-bar.toml", &out, &["--set", "solver.end_time=1e-5"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = run(BAR, &out, &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(err.contains("already holds the results of case pulled-bar.toml"), "{err}");
    assert!(!out.join("elastic-bar.pvd").exists(), "the refused run wrote nothing");

    let o = run(BAR, &out, &["--overwrite", "--resume"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("'--overwrite' cannot be used with '--resume"), "{err}");
}

/// `/`, however spelt, the home directory, the case file's own folder and
/// an existing file are refused, with or without `--overwrite`, naming the
/// path and why.
#[test]
fn dangerous_targets_are_refused_naming_the_path() {
    for root_dir in ["/", "/tmp/.."] {
        let existed = Path::new("/history.csv").exists();
        let o = femdem(&["run", BAR, "--out", root_dir, "--overwrite"]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{root_dir}");
        assert!(err.contains(&format!("refusing to write results into {root_dir}")), "{err}");
        assert!(err.contains("the root of the file system"), "{err}");
        assert_eq!(Path::new("/history.csv").exists(), existed, "nothing was written into /");
    }

    let dir = fresh("outdir-dangerous");
    std::fs::create_dir_all(&dir).unwrap();
    let home = dir.join("home");
    std::fs::create_dir_all(&home).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_femdem"))
        .args(["run", BAR, "--out", home.to_str().unwrap()])
        .env("HOME", &home)
        .current_dir(root())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("it is the home directory"), "{err}");
    assert!(err.contains(home.to_str().unwrap()), "{err}");

    let case = dir.join("bar.toml");
    std::fs::copy(root().join(BAR), &case).unwrap();
    for args in [vec!["--out", dir.to_str().unwrap()], vec!["--set", "output.dir=\".\""]] {
        let o = femdem(&[&["run", case.to_str().unwrap()][..], &args].concat());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?}");
        assert!(err.contains("it is the folder of the case file") && err.contains("bar.toml"), "{args:?}: {err}");
    }
    assert!(!dir.join("history.csv").exists());

    let file = dir.join("a-file");
    std::fs::write(&file, "not a folder").unwrap();
    let o = run(BAR, &file, &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(err.contains(&format!("output directory {}: it exists and is not a directory", file.display())), "{err}");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "not a folder");
}

/// A run takes its output directory with an exclusive lock on
/// `.femdem.lock` for as long as it writes there: while another process
/// holds it (here the test, standing for a run started in parallel with the
/// same `--out`), a run is refused, naming the directory, and writes
/// nothing; once it is released the run goes ahead, and the lock file is
/// neither a result nor a stray file to the next run's check.
#[test]
fn a_directory_another_run_is_writing_is_refused() {
    let out = fresh("outdir-locked");
    std::fs::create_dir_all(&out).unwrap();
    let held = std::fs::File::create(out.join(".femdem.lock")).unwrap();
    held.lock().unwrap();
    let o = run(BAR, &out, &["--set", "solver.end_time=1e-5"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "a run went ahead in a locked directory");
    assert!(
        err.contains(&format!("output directory {} is being written by another femdem run", out.display())),
        "{err}"
    );
    assert!(!out.join("history.csv").exists());
    held.unlock().unwrap();
    let o = run(BAR, &out, &["--set", "solver.end_time=1e-5"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let again = run(BAR, &out, &["--set", "solver.end_time=1e-5"]);
    let err = String::from_utf8_lossy(&again.stderr);
    assert!(err.contains("already holds the results of an earlier run of this case"), "{err}");
    assert!(!err.contains(".femdem.lock"), "{err}");
}
