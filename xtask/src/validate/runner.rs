//! Running `femdem run` on a generated case, as a user would: reusing a run
//! that already finished with the same case text, and resuming one that was
//! interrupted from its latest checkpoint.

use std::path::{Path, PathBuf};
use std::process::{Child, Command};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::time::{Duration, Instant};

use anyhow::{Context, Result, bail};
use toml::{Table, Value};

/// Wall-clock seconds between the checkpoints of every validation run
/// (`[output.checkpoint] interval_wall`, unless the case sets it): a paper
/// profile run interrupted after hours loses at most this much.
pub const CHECKPOINT_WALL: f64 = 600.0;

/// Seconds between updates of a run's `elapsed` file while it runs.
const ELAPSED_EVERY: Duration = Duration::from_secs(5);

/// The `femdem` binary this validation uses.
#[derive(Debug, Clone)]
pub struct Femdem {
    bin: PathBuf,
    stop: Arc<Stop>,
}

/// What validate does when asked to stop (SIGINT, SIGTERM, SIGHUP): while
/// a femdem runs, it asks that run in turn (SIGTERM), so that it writes
/// its checkpoint and ends instead of running on without validate, and
/// starts no other; with no run going, or at a second signal, it exits at
/// once (status 130).
#[derive(Debug, Default)]
struct Stop {
    /// A signal has come.
    asked: AtomicBool,
    /// How many signals have come.
    signals: AtomicU32,
    /// A femdem run is going.
    running: AtomicBool,
}

impl Stop {
    fn asked(&self) -> bool {
        self.asked.load(Ordering::SeqCst)
    }

    /// The signal handler's work.
    fn signal(&self) {
        let n = self.signals.fetch_add(1, Ordering::SeqCst) + 1;
        self.asked.store(true, Ordering::SeqCst);
        if n >= 2 || !self.running.load(Ordering::SeqCst) {
            eprintln!("validate: interrupted");
            std::process::exit(130);
        }
    }
}

/// What one run left behind.
#[derive(Debug, Clone)]
pub struct RunOutput {
    /// The run's output directory (`history.csv`, `failures.csv`, frames).
    pub dir: PathBuf,
    /// The case file's stem (the frames are `<stem>_*.vtu`).
    pub stem: String,
    /// The case file the run ran.
    pub case: PathBuf,
    /// Wall time of the run, s (of the earlier run when reused), summed
    /// over its attempts when it was resumed.
    pub wall: f64,
    /// Whether the results are those of an earlier, finished run.
    pub reused: bool,
    /// How many times the run was continued from a checkpoint.
    pub resumed: u32,
}

impl RunOutput {
    /// How the run's results were obtained, for a report's wall-time
    /// column: `""`, `" (reused)"` or `" (resumed N×)"`.
    pub fn provenance(&self) -> String {
        match (self.reused, self.resumed) {
            (true, _) => " (reused)".into(),
            (false, 0) => String::new(),
            (false, n) => format!(" (resumed {n}×)"),
        }
    }
}

impl RunOutput {
    /// The pieces the run's breakable regions had broken into at its end
    /// (`femdem_post::fragments` on the case's jointed mesh, rebuilt by
    /// the case library, and the joints of `failures.csv`), largest first.
    /// Validate runs its cases without `--set`, so the case file alone
    /// rebuilds the run's mesh.
    pub fn fragments(&self) -> Result<Vec<femdem_post::fragments::Fragment>> {
        let loaded = femdem_case::load(&self.case, &[])?;
        let (_, _, jointed) = femdem_case::prepare::jointed(&loaded)?;
        let failed = femdem_post::failures::Failure::read_all(&self.dir)?;
        femdem_post::fragments::breakable_fragments(&jointed, &failed)
    }
}

/// One line on `fragments`: how many, and the shares of the volume the
/// largest two hold.
pub fn fragments_line(fragments: &[femdem_post::fragments::Fragment]) -> String {
    let total: f64 = fragments.iter().map(|f| f.volume).sum::<f64>().max(f64::MIN_POSITIVE);
    let share = |i: usize| fragments.get(i).map_or(0.0, |f| 100.0 * f.volume / total);
    format!(
        "{} fragments of the breakable regions at the end (connected pieces: femdem_post::fragments); the largest \
         holds {:.1}% of their volume, the second {:.1}%",
        fragments.len(),
        share(0),
        share(1)
    )
}

/// The bookkeeping files of a run directory.
struct Files {
    case: PathBuf,
    out: PathBuf,
    /// Written when the run has finished: its total wall time.
    finished: PathBuf,
    /// Wall time of all attempts so far and how many were resumes,
    /// rewritten every few seconds while a run goes on.
    elapsed: PathBuf,
    log: PathBuf,
}

impl Files {
    fn new(dir: &Path, stem: &str) -> Files {
        Files {
            case: dir.join(format!("{stem}.toml")),
            out: dir.join("out"),
            finished: dir.join("finished"),
            elapsed: dir.join("elapsed"),
            log: dir.join("run.log"),
        }
    }

    /// `(seconds, resumes)` of the earlier attempts.
    fn elapsed(&self) -> (f64, u32) {
        let text = std::fs::read_to_string(&self.elapsed).unwrap_or_default();
        let mut words = text.split_whitespace();
        let seconds = words.next().and_then(|w| w.parse().ok()).unwrap_or(0.0);
        let resumes = words.next().and_then(|w| w.parse().ok()).unwrap_or(0);
        (seconds, resumes)
    }
}

/// Whether `out` holds a checkpoint femdem can continue from (a file
/// `checkpoint_<step>.femdem-ckpt`; femdem itself checks that it is
/// complete and belongs to the case).
pub fn has_checkpoint(out: &Path) -> bool {
    std::fs::read_dir(out).is_ok_and(|entries| {
        entries
            .filter_map(|e| e.ok())
            .any(|e| femdem_run::checkpoint::is_checkpoint_name(&e.file_name().to_string_lossy()))
    })
}

/// `case` with `[output.checkpoint] interval_wall` set to
/// [`CHECKPOINT_WALL`] unless it sets one; its leading comment lines kept.
pub fn with_checkpoints(case: &str) -> Result<String> {
    let mut table: Table = case.parse().context("parsing a generated case")?;
    let output = table.entry("output").or_insert_with(|| Value::Table(Table::new()));
    let output = output.as_table_mut().context("`output` is not a table")?;
    let checkpoint = output.entry("checkpoint").or_insert_with(|| Value::Table(Table::new()));
    let checkpoint = checkpoint.as_table_mut().context("`output.checkpoint` is not a table")?;
    if checkpoint.contains_key("interval_wall") {
        return Ok(case.to_string());
    }
    checkpoint.insert("interval_wall".into(), CHECKPOINT_WALL.into());
    let header: String = case.lines().take_while(|l| l.starts_with('#')).map(|l| format!("{l}\n")).collect();
    Ok(format!("{header}{}", toml::to_string(&table)?))
}

/// The `femdem` to run: the prebuilt binary the environment names in
/// `FEMDEM_BIN` (a machine without cargo, a cluster node, an earlier build
/// to measure against), or else `femdem` built in release mode. `task`
/// prefixes the line that says a prebuilt one is used.
pub fn binary(task: &str) -> Result<PathBuf> {
    if let Some(bin) = std::env::var_os("FEMDEM_BIN") {
        let bin = PathBuf::from(bin);
        if !bin.is_file() {
            bail!("FEMDEM_BIN = {} is not a file", bin.display());
        }
        eprintln!("{task}: using the prebuilt {} (FEMDEM_BIN)", bin.display());
        return Ok(bin);
    }
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    crate::run_in_root(Command::new(cargo).args(["build", "--release", "--quiet", "-p", "femdem-cli"]))?;
    let target = std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| crate::root().join("target"), PathBuf::from);
    let bin = target.join("release").join(if cfg!(windows) { "femdem.exe" } else { "femdem" });
    if !bin.exists() {
        bail!("{} was not built", bin.display());
    }
    Ok(bin)
}

impl Femdem {
    /// Builds `femdem` in release mode and returns it; or, when the
    /// environment names a prebuilt binary in `FEMDEM_BIN` (a machine
    /// without cargo, a cluster node), returns that one unbuilt.
    pub fn build() -> Result<Femdem> {
        let stop = Arc::new(Stop::default());
        {
            let stop = stop.clone();
            // A second handler cannot be installed; then a signal ends
            // validate as usual (and femdem only if sent to its group too).
            let _ = ctrlc::set_handler(move || stop.signal());
        }
        let bin = binary("validate")?;
        Ok(Femdem { bin, stop })
    }

    /// A `femdem` at `bin` (for tests).
    #[cfg(test)]
    pub fn at(bin: PathBuf) -> Femdem {
        Femdem { bin, stop: Arc::new(Stop::default()) }
    }

    /// Writes `case` (with checkpoints every [`CHECKPOINT_WALL`] s, see
    /// [`with_checkpoints`]) to `dir/<stem>.toml` and runs it with
    /// `--out dir/out`, logging to `dir/run.log`.
    ///
    /// - A run that finished before with the same case text is not repeated
    ///   (its results are reused): an interrupted validation goes on at the
    ///   first unfinished run.
    /// - A run of the same case text that did not finish (the machine's
    ///   time ran out, a signal, a crash) continues from its latest
    ///   checkpoint with `femdem run --resume`, whose results are those of
    ///   an uninterrupted run; the log is appended to.
    /// - Otherwise the run starts over (`--overwrite`).
    /// - When validate is asked to stop while femdem runs, femdem is sent
    ///   SIGTERM, writes its checkpoint and ends, and this returns an error
    ///   that says to run the same command again to resume.
    pub fn run(&self, dir: &Path, stem: &str, case: &str) -> Result<RunOutput> {
        if self.stop.asked() {
            bail!("validate was asked to stop before femdem run in {}", dir.display());
        }
        let case = with_checkpoints(case)?;
        std::fs::create_dir_all(dir)?;
        let files = Files::new(dir, stem);
        let same = std::fs::read_to_string(&files.case).is_ok_and(|c| c == case);
        let done = same.then(|| std::fs::read_to_string(&files.finished).ok()?.trim().parse::<f64>().ok()).flatten();
        if let Some(wall) = done {
            eprintln!("validate: reusing the finished run in {}", dir.display());
            let (_, resumed) = files.elapsed();
            return Ok(RunOutput { dir: files.out, stem: stem.into(), case: files.case, wall, reused: true, resumed });
        }
        let _ = std::fs::remove_file(&files.finished);
        let resume = same && has_checkpoint(&files.out);
        let (before, resumes) = if resume { files.elapsed() } else { (0.0, 0) };
        let resumes = resumes + u32::from(resume);
        let mut command = Command::new(&self.bin);
        command.arg("run").arg(&files.case).arg("--out").arg(&files.out);
        let log = if resume {
            eprintln!("validate: femdem run {} --resume (from its latest checkpoint)", files.case.display());
            command.arg("--resume");
            std::fs::OpenOptions::new().append(true).create(true).open(&files.log)?
        } else {
            std::fs::write(&files.case, &case)?;
            // A generator's mistake names its line and key here, before a
            // femdem starts (the same reader femdem runs it with).
            femdem_case::load(&files.case, &[]).context("validate generated a case femdem cannot read")?;
            eprintln!("validate: femdem run {}", files.case.display());
            command.arg("--overwrite");
            std::fs::File::create(&files.log)?
        };
        self.stop.running.store(true, Ordering::SeqCst);
        let child = command.stdout(log.try_clone()?).stderr(log).spawn();
        let waited = child
            .with_context(|| format!("starting {}", self.bin.display()))
            .and_then(|child| wait_counting(child, &files, before, resumes, &self.stop.asked));
        self.stop.running.store(false, Ordering::SeqCst);
        let (status, wall) = waited?;
        if self.stop.asked() && !status.success() {
            let then = if has_checkpoint(&files.out) {
                "its latest checkpoint is kept; run the same command again to resume"
            } else {
                "it left no checkpoint; the same command will start it over"
            };
            bail!("validate was asked to stop: femdem run {} ended ({status}); {then}", files.case.display());
        }
        if !status.success() {
            let hint = if resume {
                format!("; if its checkpoint cannot be continued, remove {} to start the run over", dir.display())
            } else {
                String::new()
            };
            bail!("femdem run {} failed ({status}); see {}{hint}", files.case.display(), files.log.display());
        }
        std::fs::write(&files.finished, format!("{wall}\n"))?;
        Ok(RunOutput { dir: files.out, stem: stem.into(), case: files.case, wall, reused: false, resumed: resumes })
    }
}

/// Waits for `child`, rewriting `files.elapsed` with `before` plus its wall
/// time every [`ELAPSED_EVERY`], so that a validation killed with its run
/// still knows how long the run took; returns the exit status and the total.
/// Once `stop` is set, the child is sent SIGTERM (femdem's signal to write
/// its checkpoint and end) and waited for.
fn wait_counting(
    mut child: Child,
    files: &Files,
    before: f64,
    resumes: u32,
    stop: &AtomicBool,
) -> Result<(std::process::ExitStatus, f64)> {
    let start = Instant::now();
    let mut last = Instant::now();
    let mut asked = false;
    let write = |seconds: f64| std::fs::write(&files.elapsed, format!("{seconds} {resumes}\n"));
    write(before)?;
    loop {
        if !asked && stop.load(Ordering::SeqCst) {
            asked = true;
            eprintln!("validate: stopping; asking femdem (pid {}) to write its checkpoint and end", child.id());
            terminate(&mut child);
        }
        if let Some(status) = child.try_wait()? {
            let total = before + start.elapsed().as_secs_f64();
            write(total)?;
            return Ok((status, total));
        }
        if last.elapsed() >= ELAPSED_EVERY {
            write(before + start.elapsed().as_secs_f64())?;
            last = Instant::now();
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// Sends `child` SIGTERM (the shell's `kill -TERM`, which femdem answers by
/// writing its checkpoint), or kills it if that cannot be sent. Elsewhere
/// than on Unix nothing is sent: a console's Ctrl-C reaches femdem itself.
fn terminate(child: &mut Child) {
    #[cfg(unix)]
    {
        let command = format!("kill -TERM {}", child.id());
        if !Command::new("sh").arg("-c").arg(command).status().is_ok_and(|s| s.success()) {
            let _ = child.kill();
        }
    }
    #[cfg(not(unix))]
    let _ = child;
}

#[cfg(all(test, unix))]
mod tests {
    //! The runner's decisions (start, reuse, resume, start over), with a
    //! stand-in `femdem`: a shell script that records its arguments and
    //! either leaves a checkpoint and fails (an interrupted run) or
    //! succeeds. That `--resume` continues bit for bit is femdem's own
    //! test (`tests/cli`).

    use super::*;
    use std::os::unix::fs::PermissionsExt;

    /// A fresh directory under the system's temporary one.
    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("xtask-runner-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// A stand-in femdem: appends its arguments to `calls`; fails after
    /// writing a checkpoint into `--out` while the file `interrupt` exists.
    fn stand_in(dir: &Path) -> Femdem {
        let bin = dir.join("femdem");
        let script = format!(
            "#!/bin/sh\necho \"$@\" >> {calls}\nout=$4\nmkdir -p \"$out\"\necho attempt\n\
             if [ -e {interrupt} ]; then touch \"$out/checkpoint_000000000010.femdem-ckpt\"; exit 3; fi\nexit 0\n",
            calls = dir.join("calls").display(),
            interrupt = dir.join("interrupt").display(),
        );
        std::fs::write(&bin, script).unwrap();
        std::fs::set_permissions(&bin, std::fs::Permissions::from_mode(0o755)).unwrap();
        Femdem::at(bin)
    }

    fn calls(dir: &Path) -> Vec<String> {
        std::fs::read_to_string(dir.join("calls")).unwrap_or_default().lines().map(String::from).collect()
    }

    /// A case the case library reads (the stand-in femdem does not run it).
    const CASE: &str = include_str!("../../../crates/femdem-cli/tests/cases/small_brazilian.toml");

    /// `CASE` with another end time.
    fn changed(end_time: &str) -> String {
        CASE.replacen("end_time = 2.0e-4", &format!("end_time = {end_time}"), 1)
    }

    #[test]
    fn an_interrupted_run_is_resumed_then_reused_and_a_changed_case_starts_over() {
        let dir = scratch("resume");
        let femdem = stand_in(&dir);
        let run_dir = dir.join("v1");

        std::fs::write(dir.join("interrupt"), "").unwrap();
        let err = femdem.run(&run_dir, "case", CASE).unwrap_err().to_string();
        assert!(err.contains("failed"), "{err}");
        assert!(!err.contains("remove"), "a first attempt has nothing to resume: {err}");
        assert!(calls(&dir)[0].ends_with("--overwrite"), "{:?}", calls(&dir));
        assert!(has_checkpoint(&run_dir.join("out")));
        assert!(!run_dir.join("finished").exists());

        // Interrupted again while resuming: the error says how to start over.
        let err = femdem.run(&run_dir, "case", CASE).unwrap_err().to_string();
        assert!(err.contains("remove") && err.contains("start the run over"), "{err}");
        assert!(calls(&dir)[1].ends_with("--resume"), "{:?}", calls(&dir));

        std::fs::remove_file(dir.join("interrupt")).unwrap();
        let out = femdem.run(&run_dir, "case", CASE).unwrap();
        assert!(calls(&dir)[2].ends_with("--resume"), "{:?}", calls(&dir));
        assert_eq!((out.reused, out.resumed), (false, 2));
        assert_eq!(out.provenance(), " (resumed 2×)");
        let log = std::fs::read_to_string(run_dir.join("run.log")).unwrap();
        assert_eq!(log.matches("attempt").count(), 3, "the log of every attempt is kept: {log}");
        let (elapsed, resumes) = Files::new(&run_dir, "case").elapsed();
        assert_eq!(resumes, 2);
        assert!(elapsed >= 0.0 && (elapsed - out.wall).abs() < 1e-9);

        let again = femdem.run(&run_dir, "case", CASE).unwrap();
        assert_eq!(calls(&dir).len(), 3, "a finished run is not run again");
        assert!(again.reused && again.provenance() == " (reused)");
        assert_eq!(again.wall, out.wall);

        let fresh = femdem.run(&run_dir, "case", &changed("3.0e-4")).unwrap();
        assert!(calls(&dir)[3].ends_with("--overwrite"), "{:?}", calls(&dir));
        assert_eq!((fresh.reused, fresh.resumed), (false, 0));
        let written: Table = std::fs::read_to_string(run_dir.join("case.toml")).unwrap().parse().unwrap();
        assert_eq!(written["solver"]["end_time"].as_float(), Some(3.0e-4), "{written}");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_changed_case_starts_over_even_with_a_checkpoint() {
        let dir = scratch("changed");
        let femdem = stand_in(&dir);
        let run_dir = dir.join("v1");
        std::fs::write(dir.join("interrupt"), "").unwrap();
        assert!(femdem.run(&run_dir, "case", CASE).is_err());
        std::fs::remove_file(dir.join("interrupt")).unwrap();
        let out = femdem.run(&run_dir, "case", &changed("3.0e-4")).unwrap();
        assert!(calls(&dir)[1].ends_with("--overwrite"), "{:?}", calls(&dir));
        assert_eq!(out.resumed, 0);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_stopped_validation_stops_its_run_which_then_resumes() {
        let dir = scratch("stop");
        // A femdem that runs until SIGTERM, then leaves a checkpoint and
        // exits as femdem does when stopped (status 1); resumed, it
        // finishes at once. It says when its handler is in place (`ready`).
        let bin = dir.join("femdem");
        let script = format!(
            "#!/bin/sh\necho \"$@\" >> {calls}\nout=$4\nmkdir -p \"$out\"\n\
             if [ \"$5\" = --resume ]; then exit 0; fi\n\
             trap 'touch \"$out/checkpoint_000000000010.femdem-ckpt\"; echo stopped > {term}; exit 1' TERM\n\
             touch {ready}\ni=0\nwhile [ $i -lt 600 ]; do sleep 0.05; i=$((i+1)); done\nexit 0\n",
            calls = dir.join("calls").display(),
            term = dir.join("term").display(),
            ready = dir.join("ready").display(),
        );
        std::fs::write(&bin, script).unwrap();
        std::fs::set_permissions(&bin, std::fs::Permissions::from_mode(0o755)).unwrap();
        let femdem = Femdem::at(bin);
        let stop = femdem.stop.clone();
        let ready = dir.join("ready");
        let asker = std::thread::spawn(move || {
            let waiting = Instant::now();
            while !ready.exists() && waiting.elapsed() < Duration::from_secs(20) {
                std::thread::sleep(Duration::from_millis(20));
            }
            assert!(stop.running.load(Ordering::SeqCst), "the run is marked as going");
            stop.asked.store(true, Ordering::SeqCst);
        });
        let start = Instant::now();
        let run_dir = dir.join("v1");
        let err = femdem.run(&run_dir, "case", CASE).unwrap_err().to_string();
        asker.join().unwrap();
        assert!(err.contains("asked to stop") && err.contains("run the same command again to resume"), "{err}");
        assert!(!femdem.stop.running.load(Ordering::SeqCst));
        assert!(dir.join("term").exists(), "femdem was sent SIGTERM");
        assert!(start.elapsed() < Duration::from_secs(25), "the run was not left running to its end");
        assert!(!run_dir.join("finished").exists() && has_checkpoint(&run_dir.join("out")));
        let err = femdem.run(&dir.join("v2"), "case", CASE).unwrap_err().to_string();
        assert!(err.contains("asked to stop"), "no further run starts: {err}");
        assert_eq!(calls(&dir).len(), 1);
        // The same command again (a new validate) resumes the run.
        let again = Femdem::at(femdem.bin.clone()).run(&run_dir, "case", CASE).unwrap();
        assert!(calls(&dir)[1].ends_with("--resume"), "{:?}", calls(&dir));
        assert_eq!((again.reused, again.resumed), (false, 1));
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_generated_case_femdem_cannot_read_is_refused_with_its_line_before_femdem_runs() {
        let dir = scratch("unreadable");
        let femdem = stand_in(&dir);
        let bad = CASE.replacen("end_time = 2.0e-4", "end_time = 2.0e-4\nend_tme = 1.0", 1);
        let err = format!("{:#}", femdem.run(&dir.join("v1"), "case", &bad).unwrap_err());
        assert!(err.contains("validate generated a case femdem cannot read") && err.contains("end_tme"), "{err}");
        assert!(calls(&dir).is_empty(), "femdem was not started");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn every_case_checkpoints_on_the_wall_clock_unless_it_says_otherwise() {
        let generated = "# generated\n[solver]\nend_time = 1.0\n";
        let with = with_checkpoints(generated).unwrap();
        assert!(with.starts_with("# generated\n"), "{with}");
        let table: Table = with.parse().unwrap();
        assert_eq!(table["output"]["checkpoint"]["interval_wall"].as_float(), Some(CHECKPOINT_WALL));
        assert_eq!(table["solver"]["end_time"].as_float(), Some(1.0));

        let own = "[output]\ninterval = 1.0\n[output.checkpoint]\ninterval_wall = 60.0\n";
        assert_eq!(with_checkpoints(own).unwrap(), own);
        let steps = "[output.checkpoint]\ninterval_steps = 100\n";
        let table: Table = with_checkpoints(steps).unwrap().parse().unwrap();
        assert_eq!(table["output"]["checkpoint"]["interval_steps"].as_integer(), Some(100));
        assert_eq!(table["output"]["checkpoint"]["interval_wall"].as_float(), Some(CHECKPOINT_WALL));
    }
}
