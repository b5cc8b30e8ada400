//! Checkpoints and `femdem run --resume` end to end, on the small Brazilian
//! disc (792 tets, contact between the platens and the disc from the start,
//! the first joint failures at step ~760, the run ending past the peak at
//! step 1844): a run stopped at step 1000 — as SIGTERM stops it, through the
//! test-only `--stop-after-steps` — with joints failed and contact active,
//! then resumed, writes `history.csv`, `failures.csv`, both `.pvd` series
//! and every frame byte for byte as the uninterrupted run does; so does a
//! resume whose newest checkpoint was left incomplete (cut in half, beside
//! a partial temporary file), from the complete one before it; so does a
//! run killed with SIGKILL while it writes a checkpoint (Unix); and a
//! checkpoint is refused to another case, naming both.

use crate::common::{col, failures, femdem, history, root};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

const CASE: &str = "crates/femdem-cli/tests/cases/small_brazilian.toml";
const STEM: &str = "small_brazilian";

fn fresh(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// The case with checkpoints every 400 steps, written under the same file
/// name (its frames are named after it) in `dir/case/`: its results are
/// those of the case.
fn with_checkpoints_every_400(dir: &Path) -> PathBuf {
    let case_dir = dir.join("case");
    std::fs::create_dir_all(&case_dir).unwrap();
    let text = std::fs::read_to_string(root().join(CASE)).unwrap();
    let case = case_dir.join(format!("{STEM}.toml"));
    std::fs::write(&case, format!("{text}\n[output.checkpoint]\ninterval_steps = 400\n")).unwrap();
    case
}

/// The uninterrupted run, once for all tests.
fn baseline() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let out = fresh("resume-baseline");
        let o = femdem(&["run", CASE, "--out", out.to_str().unwrap()]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        out
    })
}

/// Every file of the uninterrupted run (histories, series, frames) is in
/// `dir` with the same bytes.
fn assert_identical_to_baseline(dir: &Path) {
    let base = baseline();
    let mut compared = 0;
    for entry in std::fs::read_dir(base).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        let ours = std::fs::read(dir.join(&name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(ours == std::fs::read(base.join(&name)).unwrap(), "{name} differs from the uninterrupted run's");
        compared += 1;
    }
    // history, failures, 2 pvd, and frames of both series.
    assert!(compared > 10, "{compared} files compared");
}

/// Runs `case` into `out` and stops it after `steps` steps, as a signal
/// would; checks it failed with the resume hint and returns the rows of
/// its history and failure list.
fn stop_after(case: &str, out: &Path, steps: u64) -> (Vec<Vec<f64>>, usize) {
    let o = femdem(&["run", case, "--out", out.to_str().unwrap(), "--stop-after-steps", &steps.to_string()]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "a stopped run exits non-zero");
    assert!(stderr.contains("interrupted") && stderr.contains("--resume"), "{stderr}");
    assert!(out.join(format!("checkpoint_{steps:012}.femdem-ckpt")).is_file(), "no checkpoint of step {steps}");
    (history(out).rows, failures(out))
}

fn resume(case: &str, dir: &Path) -> std::process::Output {
    femdem(&["run", case, "--resume", dir.to_str().unwrap()])
}

#[test]
fn a_run_stopped_and_resumed_ends_identical_to_an_uninterrupted_one() {
    let out = fresh("resume-stopped");
    let (rows, failures) = stop_after(CASE, &out, 1000);
    // Fracture and contact were both at work before the stop: joints had
    // failed, and the contact energy was not zero.
    let contact = col(&history(&out), "contact");
    assert!(failures > 0, "no joint failed before the stop");
    assert!(rows.last().unwrap()[contact] != 0.0, "no contact work before the stop");
    let o = resume(CASE, &out);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(stderr.contains("resuming from") && stderr.contains("step 1000"), "{stderr}");
    assert_identical_to_baseline(&out);
}

#[test]
fn a_damaged_latest_checkpoint_is_skipped_for_the_complete_one_before_it() {
    // The case with checkpoints every 400 steps, under the same file name
    // (its frames are named after it); its results are those of the case.
    let dir = fresh("resume-damaged");
    let case = with_checkpoints_every_400(&dir);
    let case = case.to_str().unwrap();
    let out = dir.join("out");
    let (_, failures) = stop_after(case, &out, 1000);
    assert!(failures > 0, "no joint failed before the stop");
    let checkpoint = |n: u64| out.join(format!("checkpoint_{n:012}.femdem-ckpt"));
    assert!(checkpoint(800).is_file() && !checkpoint(400).exists(), "the two newest are kept");
    // The newest cut short, as by a crash in the middle of writing it
    // without the rename's protection, and a partial temporary file.
    let newest = std::fs::read(checkpoint(1000)).unwrap();
    std::fs::write(checkpoint(1000), &newest[..newest.len() / 2]).unwrap();
    std::fs::write(out.join(".checkpoint.tmp"), &newest[..100]).unwrap();
    let o = resume(case, &out);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(stderr.contains("skipping checkpoint") && stderr.contains("incomplete"), "{stderr}");
    assert!(stderr.contains("step 800"), "{stderr}");
    assert!(!checkpoint(1000).exists(), "the damaged checkpoint is removed once the run has gone past it");
    assert_identical_to_baseline(&out);
}

/// SIGKILL in the middle of a checkpoint write: the run, checkpointing
/// every 400 steps, is held by the hidden `--pause-checkpoint 800` between
/// writing (and syncing) the temporary file of its step-800 checkpoint and
/// renaming it, and killed there with SIGKILL — nothing of femdem runs
/// after it, as on a node failure or the OOM killer. On disk: the
/// checkpoint of step 400 and the temporary file, no checkpoint of step
/// 800. `--resume` must take step 400, remove the temporary file, and end
/// byte for byte as the uninterrupted run.
#[cfg(unix)]
#[test]
fn a_run_killed_while_writing_a_checkpoint_resumes_from_the_one_before() {
    use std::os::unix::process::ExitStatusExt;
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};

    let dir = fresh("resume-killed");
    let case = with_checkpoints_every_400(&dir);
    let case = case.to_str().unwrap();
    let out = dir.join("out");
    let mut child = Command::new(env!("CARGO_BIN_EXE_femdem"))
        .args(["run", case, "--out", out.to_str().unwrap(), "--pause-checkpoint", "800"])
        .current_dir(root())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("start femdem");
    let paused = out.join(".checkpoint.paused");
    let start = Instant::now();
    while !paused.exists() {
        if let Some(status) = child.try_wait().unwrap() {
            panic!("the run ended ({status}) without pausing in its checkpoint of step 800");
        }
        assert!(start.elapsed() < Duration::from_secs(120), "no pause within 120 s");
        std::thread::sleep(Duration::from_millis(20));
    }
    child.kill().unwrap();
    let status = child.wait().unwrap();
    assert_eq!(status.signal(), Some(9), "killed by SIGKILL: {status}");
    let checkpoint = |n: u64| out.join(format!("checkpoint_{n:012}.femdem-ckpt"));
    assert!(checkpoint(400).is_file(), "the checkpoint before is complete");
    assert!(!checkpoint(800).exists(), "killed before the rename");
    let tmp = out.join(".checkpoint.tmp");
    assert!(std::fs::metadata(&tmp).unwrap().len() > 0, "the interrupted write left its temporary file");
    let o = resume(case, &out);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(stderr.contains("resuming from") && stderr.contains("step 400"), "{stderr}");
    assert!(!tmp.exists() && !paused.exists(), "the leftovers are removed");
    assert_identical_to_baseline(&out);
}

#[test]
fn a_checkpoint_of_another_case_is_refused_naming_both() {
    let dir = fresh("resume-other-case");
    let out = dir.join("out");
    stop_after(CASE, &out, 5);
    // The same case but for one comment: another case text.
    let other = dir.join("other_brazilian.toml");
    let text = std::fs::read_to_string(root().join(CASE)).unwrap();
    std::fs::write(&other, format!("# changed\n{text}")).unwrap();
    let history_before = std::fs::read(out.join("history.csv")).unwrap();
    let o = resume(other.to_str().unwrap(), &out);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "a checkpoint of another case must be refused");
    assert!(stderr.contains("small_brazilian.toml") && stderr.contains("other_brazilian.toml"), "{stderr}");
    assert!(stderr.contains("checkpoint_000000000005.femdem-ckpt") && stderr.contains("case text differs"), "{stderr}");
    assert_eq!(std::fs::read(out.join("history.csv")).unwrap(), history_before, "the refused resume wrote nothing");
}
