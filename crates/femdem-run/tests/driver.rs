//! The run driver as a library: a case run with an observer and a stop
//! flag, as another program would run it (the command line's own tests
//! drive the same code through the `femdem` binary).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

use femdem_run::{Observer, RunOptions, Status};

/// The small Brazilian case of the command line's tests.
fn case() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../femdem-cli/tests/cases/small_brazilian.toml")
}

fn fresh(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("femdem-run-driver-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// Records what the driver tells it; sets `stop` once `stop_at` steps are
/// done.
#[derive(Default)]
struct Recorder<'a> {
    notes: Vec<String>,
    started: Option<(u64, u64, u64)>,
    last: Option<(u64, Status)>,
    ended: usize,
    stop: Option<(&'a AtomicBool, u64)>,
}

impl Observer for Recorder<'_> {
    fn note(&mut self, line: &str) {
        self.notes.push(line.to_owned());
    }

    fn started(&mut self, first: u64, total: u64, elements: u64) {
        self.started = Some((first, total, elements));
    }

    fn stepped(&mut self, steps: u64, _time: f64, status: &dyn Fn() -> Status) {
        self.last = Some((steps, status()));
        if let Some((flag, at)) = self.stop
            && steps >= at
        {
            flag.store(true, Ordering::SeqCst);
        }
    }

    fn ended(&mut self) {
        self.ended += 1;
    }
}

#[test]
fn a_run_stopped_by_its_flag_and_resumed_ends_as_an_uninterrupted_one() {
    let whole_dir = fresh("whole");
    let never = AtomicBool::new(false);
    let mut whole = Recorder::default();
    let options = RunOptions { out: Some(whole_dir.clone()), ..Default::default() };
    let s = femdem_run::run(&case(), options, &never, &mut whole).unwrap();
    let (first, total, elements) = whole.started.unwrap();
    // The case stops past its peak load (`stop_below_peak`), before its end.
    assert_eq!((first, s.interrupted), (0, false));
    assert!(s.past_peak.is_some() && s.steps < total, "{s:?}");
    let steps = s.steps;
    assert!(elements > 0 && s.throughput > 0.0);
    assert_eq!(whole.ended, 1);
    assert_eq!(whole.last.map(|l| l.0), Some(steps), "every step is reported");
    assert_eq!(whole.last.unwrap().1.failed_joints, s.failed_joints);
    assert!(whole.notes.iter().any(|n| n.contains("tets") && n.contains("steps")), "{:?}", whole.notes);
    let history = femdem_post::table::Table::history(&s.dir).unwrap();
    assert_eq!(history.col("step").unwrap().last().copied(), Some((steps - 1) as f64));

    // Stopped by the flag: a checkpoint, and the resumed run's files are
    // the uninterrupted run's, byte for byte.
    let dir = fresh("stopped");
    let flag = AtomicBool::new(false);
    let mut stopped = Recorder { stop: Some((&flag, steps / 2)), ..Default::default() };
    let options = RunOptions { out: Some(dir.clone()), ..Default::default() };
    let s = femdem_run::run(&case(), options, &flag, &mut stopped).unwrap();
    assert!(s.interrupted && s.steps < steps && s.checkpoint.is_some(), "{s:?}");
    let options = RunOptions { out: Some(dir.clone()), resume: Some(None), ..Default::default() };
    let mut resumed = Recorder::default();
    let s = femdem_run::run(&case(), options, &never, &mut resumed).unwrap();
    assert!(!s.interrupted && s.steps == steps && s.past_peak.is_some(), "{s:?}");
    assert!(resumed.notes.iter().any(|n| n.starts_with("resuming from")), "{:?}", resumed.notes);
    for file in ["history.csv", "failures.csv"] {
        assert_eq!(std::fs::read(dir.join(file)).unwrap(), std::fs::read(whole_dir.join(file)).unwrap(), "{file}");
    }
    let _ = std::fs::remove_dir_all(&whole_dir);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_run_stopped_before_its_first_step_writes_and_removes_nothing() {
    // An earlier run's results, which `overwrite` would remove.
    let dir = fresh("stopped-early");
    let options = RunOptions { out: Some(dir.clone()), stop_after_steps: Some(5), ..Default::default() };
    let first = femdem_run::run(&case(), options, &AtomicBool::new(false), &mut Recorder::default()).unwrap();
    assert!(first.interrupted);
    let history = std::fs::read(dir.join("history.csv")).unwrap();

    // The stop flag is already set when the next run starts (a signal
    // while the case meshes): it ends with an error and touches nothing.
    let options = RunOptions { out: Some(dir.clone()), overwrite: true, ..Default::default() };
    let err = femdem_run::run(&case(), options, &AtomicBool::new(true), &mut Recorder::default()).unwrap_err();
    assert!(err.to_string().contains("stopped while preparing the case, before the first step"), "{err:#}");
    assert_eq!(std::fs::read(dir.join("history.csv")).unwrap(), history, "the earlier results are kept");
    let _ = std::fs::remove_dir_all(&dir);
}
